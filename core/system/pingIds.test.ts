/**
 * Ping ids run 1…65 535 and come round again (262 s of pings at 4 ms). A ping whose
 * PONG was lost (a corrupted link) stays among those awaiting a pong; when its id comes
 * round, the new ping must be stamped afresh, not matched to the old stamp, or its round
 * trip reads minutes long and every lead and resend timeout grows with it (rttHigh).
 * The simulator's Blot with its real firmware; the lost pong is put where the session
 * keeps it (white-box: waiting 65 535 pings for one would take minutes of wall time).
 */
import { expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import { startMachine } from './harness.ts';

interface SessionInside {
  nextPingId: number;
  pings: Map<number, { at: number; frameBytes: number; resent: boolean }>;
  clock: { rttHigh: number; samples: number };
}

it('a ping id that comes round again after a lost pong is stamped afresh: the round trips stay those of the link', async () => {
  const b = await startMachine(blotPlotter(), { seed: 3 });
  const session = (b.maxl as unknown as { runtime: { sessions: SessionInside[] } }).runtime.sessions[0];
  // The pong of the ping that last had the next id was lost 262 s ago.
  session.pings.set(session.nextPingId, { at: b.scheduler.now() - 262e6, frameBytes: 10, resent: false });
  const before = session.clock.samples;
  // 100 ms: some 25 exchanges, that id's among them, all still within rttHigh's last 64.
  await b.scheduler.advance(100_000);
  expect(session.clock.samples).toBeGreaterThan(before + 10);
  expect(session.clock.rttHigh).toBeLessThan(5_000);
  await b.maxl.end();
  await b.sim.stop();
});
