/**
 * A link slower than the job (net/linkFeedLimit.ts): the Blot plotter behind an
 * Uno-like 25 kB/s UART, drawing a fine spiral (0.1 mm pieces) that at full speed
 * needs ~35 kB/s of segments. Without the limit the stream cannot keep up and the
 * job is stopped (the lead it needs holds more segments than the board's queue, or
 * timing arrives late); with it (the default) the job is slowed to what the link
 * carries and runs to the end on the path.
 */
import { describe, expect, it } from 'vitest';
import { blotPlotter } from '../sim/presets/index.ts';
import type { Move } from '../index.ts';
import { UNO_UART_LINK } from '../sim/link/linkConfig.ts';
import { runAndCheckPositions, runJob, startMachine, type Bench } from './harness.ts';

/** The board behind a 250 000 baud UART: 25 bytes per ms. */
const UART = { blot: UNO_UART_LINK };
/**
 * Streamer margins for a UART. The defaults (0.7 ms to start, 2.5 ms over 2·RTT
 * of lead) are sized for USB; on 25 kB/s a run's first GEOMETRY and TIMING frames
 * (~130 bytes) take ~5 ms, and every frame waits behind the ones before it. With
 * a 12 ms lead margin a motor fell 0.05 step outside its bound; 20 ms holds. (The
 * workbench gives real boards 80 ms.)
 */
const UART_STREAMER = { startMargin_us: 6_000, leadMargin_us: 20_000 };

/** An Archimedean spiral from the middle of the bed, a point every 0.1 mm, `turns` turns. */
function spiral(turns: number): Move[] {
  const moves: Move[] = [];
  const pitch = 2; // mm between turns
  let theta = 0.5;
  while (theta < turns * 2 * Math.PI) {
    const r = (pitch * theta) / (2 * Math.PI);
    moves.push({ endPosition: [50 + r * Math.cos(theta), 50 + r * Math.sin(theta)] });
    theta += 0.1 / Math.max(r, 0.5); // arc ≈ r·dθ = 0.1 mm
  }
  return moves;
}

async function start(options: { linkFeedLimit?: boolean; uart?: boolean }): Promise<Bench> {
  const uart = options.uart !== false;
  const b = await startMachine(blotPlotter(), {
    seed: 5,
    sim: uart ? { links: UART } : {},
    maxl: { linkFeedLimit: options.linkFeedLimit, ...(uart ? { streamer: UART_STREAMER } : {}) },
  });
  await runJob(b, [{ endPosition: [50, 50] }]);
  return b;
}

const errors = (b: Bench) => b.events.filter((e) => e.type === 'error');

describe('a link slower than the job', () => {
  it('without the feed limit, the job is too fast for the board behind a 25 kB/s UART and is stopped', async () => {
    const b = await start({ linkFeedLimit: false });
    expect(b.maxl.feedLimit?.minSegment_us).toBe(0);
    const moves = spiral(6);
    for (const m of moves) void b.maxl.addSegmentToQueue(m);
    await b.scheduler.advance(8_000_000);
    b.sim.sync();
    expect(errors(b).length).toBeGreaterThan(0);
    expect(errors(b)[0].text).toMatch(/buffer conflict|too late|ran out of timing/);
    expect(b.maxl.history.size - 1).toBeLessThan(moves.length / 2);
  });

  it('with it (the default), the spiral is slowed to what the link carries and runs to the end on the path', async () => {
    const b = await start({});
    const limit = b.maxl.feedLimit!;
    expect(limit.device).toBe('blot');
    expect(limit.bytesPerSecond).toBe(25_000);
    // two position tracks: ~29 bytes a segment, at 3/4 of 25 kB/s
    expect(limit.bytesPerSegment).toBeGreaterThan(20);
    expect(limit.minSegment_us).toBeCloseTo((limit.bytesPerSegment / (25_000 * 0.75)) * 1e6, 6);
    const moves = spiral(6);
    const r = await runAndCheckPositions(b, moves);
    expect(errors(b)).toEqual([]);
    expect(r.worstExcess).toBeLessThanOrEqual(0); // every motor within a step (plus sync) of the plan, throughout
    // Every segment of the spiral lasted at least the floor.
    const history = b.maxl.history;
    expect(history.size - 1).toBeGreaterThanOrEqual(moves.length); // the spiral after the move to the middle (long pieces go in slices)
    let shortest_us = Infinity;
    for (let i = 1; i < history.size; i++) shortest_us = Math.min(shortest_us, history.at(i).duration_s * 1e6);
    expect(shortest_us).toBeGreaterThanOrEqual(limit.minSegment_us * (1 - 1e-9));
  });

  it('a native-USB link (1.2 MB/s) hardly limits the same job', async () => {
    const b = await start({ uart: false });
    const limit = b.maxl.feedLimit!;
    expect(limit.bytesPerSecond).toBe(19 * 64 * 1000);
    expect(limit.minSegment_us).toBeLessThan(40);
  });
});
