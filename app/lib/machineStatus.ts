/**
 * What the machine is doing, in one word for the header and a sentence for the
 * banner: the worker's phase, refined by the job that runs and the tool's speed.
 * "ready" only when nothing moves and nothing waits.
 */
import type { JobProgress, MachinePhase } from '../worker/protocol.ts';

export type MachineStatus = MachinePhase | 'running' | 'pausing' | 'paused' | 'moving';

const JOB_STATUS: Partial<Record<JobProgress['phase'], MachineStatus>> = {
  loading: 'running',
  running: 'running',
  pausing: 'pausing',
  paused: 'paused',
  cancelling: 'running',
};

export function machineStatus(phase: MachinePhase | undefined, job: JobProgress | null, speed: number): MachineStatus | 'starting' {
  if (!phase) return 'starting';
  if (phase !== 'ready') return phase;
  const fromJob = job ? JOB_STATUS[job.phase] : undefined;
  if (fromJob) return fromJob;
  return speed > 0 ? 'moving' : 'ready';
}

/** Whether Re-arm can help: after STOP, a stop on the path, or a problem fixed since. */
export function needsRearm(phase: MachinePhase | undefined): boolean {
  return phase === 'halted' || phase === 'not-ready' || phase === 'stopped';
}
