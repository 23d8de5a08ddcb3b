/**
 * The capture tool on the page: what the worker says of the run, the captures kept
 * (IndexedDB), which one is shown and which is overlaid to compare, and the commands.
 */
import type { WorkbenchStore } from '../../lib/workbench.svelte.ts';
import { deleteCapture, loadCaptures } from './captureDb.ts';
import type { CaptureProgress, CaptureRecord, TestMotion } from './protocol.ts';

export class CaptureStore {
  progress = $state.raw<CaptureProgress | null>(null);
  running = $state(false);
  error = $state<string | null>(null);
  captures = $state.raw<CaptureRecord[]>([]);
  selectedId = $state<string | null>(null);
  compareId = $state<string | null>(null);

  constructor(private readonly wb: WorkbenchStore) {
    wb.client.on((e) => {
      if (!('tool' in e) || e.tool !== 'capture') return;
      if (e.type === 'capture-progress') {
        this.progress = e.progress;
      } else if (e.type === 'capture-done') {
        this.running = false;
        this.progress = null;
        this.show(e.record, e.notKept);
      } else if (e.type === 'capture-failed') {
        this.running = false;
        this.progress = null;
        this.error = e.message;
      }
    });
    void this.reload();
  }

  get selected(): CaptureRecord | null {
    return this.captures.find((c) => c.id === this.selectedId) ?? null;
  }

  get compared(): CaptureRecord | null {
    return this.compareId === this.selectedId ? null : (this.captures.find((c) => c.id === this.compareId) ?? null);
  }

  run(motion: TestMotion): void {
    this.error = null;
    this.running = true;
    this.wb.send({ tool: 'capture', type: 'capture-run', motion });
  }

  cancel(): void {
    this.wb.send({ tool: 'capture', type: 'capture-cancel' });
  }

  async remove(id: string): Promise<void> {
    await deleteCapture(id);
    this.captures = this.captures.filter((c) => c.id !== id);
    if (this.selectedId === id) this.selectedId = null;
    if (this.compareId === id) this.compareId = null;
    await this.reload();
  }

  /** Shows a finished capture at once (the worker kept it in IndexedDB, or says why not). */
  private show(record: CaptureRecord, notKept: string | null): void {
    this.captures = [record, ...this.captures.filter((c) => c.id !== record.id)];
    this.selectedId = record.id;
    if (notKept) this.error = `The capture is shown but could not be kept: ${notKept}`;
  }

  private async reload(): Promise<void> {
    try {
      const kept = await loadCaptures();
      const unsaved = this.captures.filter((c) => !kept.some((k) => k.id === c.id));
      this.captures = [...unsaved, ...kept];
    } catch (err) {
      this.error = `Kept captures could not be read: ${err instanceof Error ? err.message : String(err)}`;
    }
  }
}
