/**
 * Whether closing or reloading the page now would lose work, so that the browser
 * asks first (its `beforeunload` prompt, as editors and web G-code senders do).
 * The jobs, the tools' motion and the author itself live in this page's worker:
 * a reload ends them (a simulated machine starts again at rest; real boards brake
 * to a stop within their lead), and a stopped job can no longer be resumed.
 *
 * So it asks while a job, plot, light painting or capture runs, pauses or is
 * paused, while the machine moves (a jog, a stroke being drawn), and while a
 * stopped job could still be resumed; never when the machine rests with nothing to
 * lose, where a prompt would only be in the way.
 */
import type { JobProgress } from '../worker/protocol.ts';
import type { MachineStatus } from './machineStatus.ts';

export function leavingLosesWork(status: MachineStatus | 'starting', job: JobProgress | null): boolean {
  return status === 'running' || status === 'pausing' || status === 'paused' || status === 'moving' || job?.resumable === true;
}
