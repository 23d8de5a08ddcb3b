/**
 * The workbench's tools, by name: each one's worker module, built on the tool
 * context. Commands that carry `tool` go to the tool of that name.
 */
import type { ToolContext, WorkbenchTool } from './toolContext.ts';
import type { ToolCommand } from './protocol.ts';
import { CaptureTool } from '../tools/capture/captureTool.ts';

export function createTools(ctx: ToolContext): Map<string, WorkbenchTool<ToolCommand>> {
  const tools = new Map<string, WorkbenchTool<ToolCommand>>();
  void ctx;
  tools.set('capture', new CaptureTool(ctx) as WorkbenchTool<ToolCommand>);
  return tools;
}
