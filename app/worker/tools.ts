/**
 * The workbench's tools, by name: each one's worker module, built on the tool
 * context. Commands that carry `tool` go to the tool of that name.
 */
import type { ToolContext, WorkbenchTool } from './toolContext.ts';
import type { ToolCommand } from './protocol.ts';
import { LightpaintTool } from '../tools/lightpaint/lightpaintTool.ts';
import { FileJobs } from '../tools/plotter/files/fileJobs.ts';

export function createTools(ctx: ToolContext): Map<string, WorkbenchTool<ToolCommand>> {
  const tools = new Map<string, WorkbenchTool<ToolCommand>>();
  tools.set('lightpaint', new LightpaintTool(ctx) as WorkbenchTool<ToolCommand>);
  // Temporary: the plotter's file commands (file-*) only, until the plotter's own router takes them.
  tools.set('plotter', new FileJobs(ctx) as WorkbenchTool<ToolCommand>);
  return tools;
}
