import { describe, expect, it } from 'vitest';
import type { JobProgress } from '../worker/protocol.ts';
import { leavingLosesWork } from './leaveGuard.ts';

const job = (phase: JobProgress['phase'], resumable = false): JobProgress => ({
  name: 'job',
  phase,
  totalSegments: 10,
  doneSegments: 3,
  totalLength: 100,
  doneLength: 30,
  eta_s: 5,
  elapsed_s: 2,
  resumable,
});

describe('leavingLosesWork (the beforeunload prompt)', () => {
  it.each(['running', 'pausing', 'paused', 'moving'] as const)('asks while the machine is %s', (status) => {
    expect(leavingLosesWork(status, null)).toBe(true);
  });

  it('asks while a stopped job can still be resumed, whatever the machine does', () => {
    expect(leavingLosesWork('halted', job('halted', true))).toBe(true);
    expect(leavingLosesWork('ready', job('failed', true))).toBe(true);
  });

  it.each(['ready', 'starting', 'connecting', 'not-ready', 'halted', 'empty'] as const)('lets the tab go when the machine is %s with nothing to resume', (status) => {
    expect(leavingLosesWork(status, null)).toBe(false);
    expect(leavingLosesWork(status, job('done'))).toBe(false);
    expect(leavingLosesWork(status, job('cancelled'))).toBe(false);
  });
});
