/**
 * Byte corruption at 10⁻² on every link (frames of 20–40 bytes fail 18–33 % of the
 * time): the two cases of the fault matrix that failed, each on the seed that showed it.
 *  - accelRig, seed 95: the start's first frames were lost and the lead had no room for
 *    their resend; the device refused the TIMING as late, five times over (the leads
 *    now cover the resends the measured loss needs: streamer.ts, resendAllowance_us).
 *  - blotPlotter, seed 78: a resent ping alone in the rate fit's last slice swung the
 *    clock model 70 µs at one refit, and a motor ran 1.655 steps behind its plan where
 *    1.631 were allowed (clockSync.ts, fitRate). That was at commit 3eda51c; firmware
 *    changes since draw other corruption, and the seed passed before the fix too: it stays
 *    as a regression case, and clockSync.test.ts tests the mechanism itself.
 * Each must run to its end without a stop, every motor on its plan within the harness's
 * bound all the way.
 */
import { describe, expect, it } from 'vitest';
import { runFaultCase, type PresetName } from './faultCases.ts';

describe('byte corruption 1e-2: the job runs through, on its plan', () => {
  for (const [preset, seed] of [['accelRig', 95], ['blotPlotter', 78]] as Array<[PresetName, number]>) {
    it(`${preset}, seed ${seed}`, async () => {
      const r = await runFaultCase({ preset, kind: 'corrupt', seed, at: 0, corruption: 1e-2 });
      expect(r.resends).toBeGreaterThan(1000);
      expect(r.reasons).toEqual([]);
      expect(r.lateSteps).toBeLessThanOrEqual(0);
      expect(r.resumed).toBe(true);
      expect(r.endError_mm).toBeLessThanOrEqual(0.02);
    }, 120_000);
  }
});
