/**
 * The workbench's tools, by name: each one's worker module, built on the tool
 * context. Commands that carry `tool` go to the tool of that name.
 */
import type { ToolContext, WorkbenchTool } from './toolContext.ts';
import type { ToolCommand } from './protocol.ts';
import { LightpaintTool } from '../tools/lightpaint/lightpaintTool.ts';
import { PlotterTool } from '../tools/plotter/plotterTool.ts';
import { CaptureTool } from '../tools/capture/captureTool.ts';

export function createTools(ctx: ToolContext): Map<string, WorkbenchTool<ToolCommand>> {
  const tools = new Map<string, WorkbenchTool<ToolCommand>>();
  tools.set('plotter', new PlotterTool(ctx) as WorkbenchTool<ToolCommand>);
  tools.set('lightpaint', new LightpaintTool(ctx) as WorkbenchTool<ToolCommand>);
  tools.set('capture', new CaptureTool(ctx) as WorkbenchTool<ToolCommand>);
  return tools;
}
