/**
 * Event channels and sensors end to end:
 *  - the light painter's LEDs change within one evaluation tick of the plan;
 *  - accelerometer samples, stamped with the board's clock and mapped into author
 *    time, line up with when the board really read them, within 1 ms.
 */
import { describe, expect, it } from 'vitest';
import { accelRig, lightPainter } from '../sim/presets/index.ts';
import { runJob, startMachine } from './harness.ts';
import { queueOf } from '../maxl.ts';

describe('event channels', () => {
  it('LED changes fire within one evaluation tick of the plan', async () => {
    const b = await startMachine(lightPainter(), { sim: { outputLogSize: 100_000 } });
    const TICK_MS = 10;
    // "HELLO"-style stripes: a different bit pattern every 4 mm of x.
    const stripes = (x: number) => [0x81, 0x42, 0x24, 0x18][Math.floor(x / 4) % 4];
    // Each segment's changes, once (a segment may be reported transmitted again when
    // its timing is resent), then only real changes: the strip shows each change once.
    const bySegment = new Map<number, Array<{ t: number; value: number }>>();
    queueOf(b.maxl).subscribe((e) => {
      if (e.type !== 'transmitted') return;
      for (const seg of e.segments) {
        const changes: Array<{ t: number; value: number }> = [];
        for (const track of queueOf(b.maxl).eventTracksOf(seg)) track.times.forEach((t, k) => changes.push({ t: seg.startTime_us + t * 1e6, value: track.values[k] }));
        bySegment.set(seg.id, changes);
      }
    });
    const jobStart = b.scheduler.now();
    const eventChannels = [{ name: 'neopixelBitmap', evaluationPrecision: TICK_MS, evaluator: (s: { position: Record<string, number> }) => stripes(s.position.x) }];
    await runJob(b, [{ endPosition: [20, 20] }, { endPosition: [90, 20], maxVelocity: 60, eventChannels }, { endPosition: [90, 30] }]);
    // What the strip showed, and when: each LED i lit means bit i.
    const shows = b.sim.devices.lightPainter.outputs
      .filter((o) => o.kind === 'led' && o.t_us > jobStart)
      .map((o) => {
        const rgb = (o as { rgb: Uint8Array }).rgb;
        let value = 0;
        for (let i = 0; i < 8; i++) if (rgb[3 * i] > 0) value |= 1 << i;
        return { t: o.t_us, value };
      });
    const planned: Array<{ t: number; value: number }> = [];
    for (const id of [...bySegment.keys()].sort((a, c) => a - c)) {
      for (const change of bySegment.get(id)!) if (planned.length === 0 || planned[planned.length - 1].value !== change.value) planned.push(change);
    }
    expect(planned.length).toBeGreaterThan(15);
    expect(shows.length).toBe(planned.length);
    let worst = 0;
    shows.forEach((s, k) => {
      expect(s.value).toBe(planned[k].value);
      worst = Math.max(worst, Math.abs(s.t - planned[k].t));
    });
    expect(worst).toBeLessThan(TICK_MS * 1000);
    expect(worst).toBeLessThan(500); // in fact: the clock error and a loop period
    await b.sim.stop();
  }, 60_000);
});

describe('sensor capture', () => {
  it('samples stamped by the board line up with when it read them, within 1 ms, and export as CSV', async () => {
    const b = await startMachine(accelRig(), { sim: { outputLogSize: 200_000 } });
    await runJob(b, [{ endPosition: [100] }, { endPosition: [20] }, { endPosition: [60] }]);
    const capture = b.maxl.captures.get('accelerometer/accel');
    expect(capture).toBeDefined();
    const times = capture!.timeColumn();
    expect(times.length).toBeGreaterThan(100);
    expect(capture!.gaps).toEqual([]);
    // The board's reads of the acceleration registers, in author time (ground truth).
    const reads = b.sim.devices.accelerometer.outputs.filter((o) => o.kind === 'i2cRead').map((o) => o.t_us);
    let worst = 0;
    let r = 0;
    for (const t of times) {
      while (r + 1 < reads.length && Math.abs(reads[r + 1] - t) <= Math.abs(reads[r] - t)) r++;
      worst = Math.max(worst, Math.abs(reads[r] - t));
    }
    expect(worst).toBeLessThan(1000);
    // The CSV joins each sample with the plan at its time.
    const csv = b.maxl.captureCsv('accelerometer/accel', ['ax', 'ay', 'az']).split('\n');
    expect(csv[0]).toBe(
      't_s,author_us,device_us,batch,index_in_batch,sample_seq,lost_before,ax,ay,az,planned_x_mm,planned_vx_mm_s,planned_ax_mm_s2,planned_speed_mm_s,planned_path_accel_mm_s2',
    );
    expect(csv.length).toBe(times.length + 1);
    const mid = csv[Math.floor(csv.length / 2)].split(',').map(Number);
    expect(mid[10]).toBeCloseTo(b.maxl.sample(mid[1]).position[0], 6);
    await b.sim.stop();
  }, 60_000);
});
