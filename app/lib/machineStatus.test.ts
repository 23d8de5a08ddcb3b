import { describe, expect, it } from 'vitest';
import { machineStatus, needsRearm } from './machineStatus.ts';
import type { JobProgress } from '../worker/protocol.ts';

const job = (phase: JobProgress['phase']): JobProgress => ({ name: 'j', phase, totalSegments: 1, doneSegments: 0, totalLength: 1, doneLength: 0, eta_s: 1, elapsed_s: 0, resumable: false });

describe('machineStatus', () => {
  it('says what a ready machine is doing', () => {
    expect(machineStatus('ready', null, 0)).toBe('ready');
    expect(machineStatus('ready', null, 12)).toBe('moving');
    expect(machineStatus('ready', job('running'), 40)).toBe('running');
    expect(machineStatus('ready', job('paused'), 0)).toBe('paused');
    expect(machineStatus('ready', job('pausing'), 5)).toBe('pausing');
    // A finished job leaves the machine ready.
    expect(machineStatus('ready', job('done'), 0)).toBe('ready');
  });

  it('a phase that is not ready wins over a job', () => {
    expect(machineStatus('stopped', job('running'), 0)).toBe('stopped');
    expect(machineStatus('halted', job('running'), 0)).toBe('halted');
    expect(machineStatus(undefined, null, 0)).toBe('starting');
  });

  it('Re-arm is offered after a stop of any kind', () => {
    expect(['halted', 'not-ready', 'stopped', 'ready', 'connecting', 'empty'].filter((p) => needsRearm(p as never))).toEqual(['halted', 'not-ready', 'stopped']);
  });
});
