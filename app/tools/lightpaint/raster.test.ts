import { describe, expect, it } from 'vitest';
import type { EvaluatorState, LinearMove, EventEvaluatorSpec } from '../../../core/index.ts';
import { textBitmap } from './bitmap.ts';
import { PASS_PIECE_MM, PASS_PIECE_S, bitmapEvaluator, columnAt, isProblem, planRaster, runUpLength, type RasterMachine, type RasterPlan, type RasterSettings } from './raster.ts';

const machine: RasterMachine = {
  motionAxes: ['x', 'y'],
  eventChannels: ['neopixelBitmap', 'neopixelColour', 'neopixelCruise'],
  origin: [20, 100],
  softMin: [0, 0],
  softMax: [300, 200],
  maxSpeed: 200,
  maxAccel: 2000,
};
const settings: RasterSettings = { speed: 100, pitch_mm: 2, colour: [255, 60, 10], reverse: false, evaluationPrecision_ms: 0.5 };

function state(x: number, v: number, a: number): EvaluatorState {
  return { time: 0, duration: 1, distance: 0, moveDistance: 0, position: { x, y: 100 }, velocity: [v, 0], acceleration: [a, 0], speed: Math.abs(v), unit: [1, 0] };
}

describe('raster', () => {
  it('columns are half-open pitch-wide intervals from x0', () => {
    expect(columnAt(10, 10, 2, 3)).toBe(0);
    expect(columnAt(11.999, 10, 2, 3)).toBe(0);
    expect(columnAt(12, 10, 2, 3)).toBe(1);
    expect(columnAt(16, 10, 2, 3)).toBe(-1);
    expect(columnAt(9.99, 10, 2, 3)).toBe(-1);
  });

  it('the evaluator answers for the middle of its hold interval, from position, velocity and acceleration', () => {
    const layout = { x0: 10, pitch_mm: 2, bits: [1, 2, 4], y: 100, xStart: 9, xEnd: 17 };
    const ev = bitmapEvaluator(layout, 'x', 0, 1);
    // At 11.95 mm moving +100 mm/s, the middle of the next ms is at 12.0 mm: column 1.
    expect(ev(state(11.95, 100, 0))).toBe(2);
    expect(ev(state(11.94, 100, 0))).toBe(1);
    // Accelerating from rest at 2000 mm/s²: x + a·h²/2 with h = 0.5 ms moves 0.25 µm.
    expect(ev(state(11.99975, 0, 2000))).toBe(2);
    // Moving left (reverse): the column behind.
    expect(ev(state(12.04, -100, 0))).toBe(1);
    expect(ev(state(5, 100, 0))).toBe(0);
  });

  it('plans a travel to the start with the strip dark, then one pass that sets colour and cruise', () => {
    const plan = planRaster(textBitmap('HI', 8), settings, machine) as RasterPlan;
    expect(isProblem(plan)).toBe(false);
    expect(plan.runUp_mm).toBe(runUpLength(100, 2000));
    expect(plan.layout.x0).toBeCloseTo(20 + plan.runUp_mm, 9);
    const [travel, ...pieces] = plan.moves as LinearMove[];
    expect(travel.endPosition).toEqual([20, 100]);
    expect(travel.eventChannels).toEqual({ neopixelBitmap: 0 });
    // 22.2 mm in two collinear pieces of at most PASS_PIECE_MM, each with the same channels.
    expect(pieces).toHaveLength(Math.ceil((2 * plan.runUp_mm + 22) / PASS_PIECE_MM));
    expect(pieces.map((p) => p.endPosition)).toEqual([[20 + plan.runUp_mm + 11, 100], [20 + 2 * plan.runUp_mm + 11 * 2, 100]]);
    for (const p of pieces) expect(p.eventChannels).toBe(pieces[0].eventChannels);
    const pass = pieces[0];
    const events = pass.eventChannels as Array<EventEvaluatorSpec | { name: string; value: number }>;
    expect(events.map((e) => e.name)).toEqual(['neopixelBitmap', 'neopixelColour', 'neopixelCruise']);
    expect(events[1]).toEqual({ name: 'neopixelColour', value: 0xff3c0a });
    expect(events[2]).toEqual({ name: 'neopixelCruise', value: 100 });
    expect((events[0] as EventEvaluatorSpec).evaluationPrecision).toBe(0.5);
  });

  it('a slow pass is queued in pieces of at most PASS_PIECE_S, and the travel to its start runs at the top speed', () => {
    for (const speed of [0.5, 2, 20, 100, 200]) {
      const plan = planRaster(textBitmap('HI', 8), { ...settings, speed }, machine) as RasterPlan;
      const [travel, ...pieces] = plan.moves as LinearMove[];
      expect(travel.maxVelocity).toBe(machine.maxSpeed);
      let x = plan.layout.xStart;
      for (const p of pieces) {
        const end = (p.endPosition as number[])[0];
        expect(end - x).toBeLessThanOrEqual(Math.min(PASS_PIECE_MM, speed * PASS_PIECE_S) + 1e-9);
        expect(p.maxVelocity).toBe(speed);
        x = end;
      }
      expect(x).toBeCloseTo(plan.layout.xEnd, 9);
    }
    // At 2 mm/s, 0.4 mm pieces: 22.2 mm in 56.
    expect((planRaster(textBitmap('HI', 8), { ...settings, speed: 2 }, machine) as RasterPlan).moves).toHaveLength(1 + 56);
  });

  it('reversed, the pass runs right to left over the same span', () => {
    const plan = planRaster(textBitmap('HI', 8), { ...settings, reverse: true }, machine) as RasterPlan;
    const moves = plan.moves as LinearMove[];
    expect(moves[0].endPosition).toEqual([plan.layout.xEnd, 100]);
    expect(moves[moves.length - 1].endPosition).toEqual([plan.layout.xStart, 100]);
    for (let k = 2; k < moves.length; k++) expect((moves[k].endPosition as number[])[0]).toBeLessThan((moves[k - 1].endPosition as number[])[0]);
  });

  it('caps the speed at the machine limit and says so', () => {
    const plan = planRaster(textBitmap('HI', 8), { ...settings, speed: 500 }, machine) as RasterPlan;
    expect(plan.speed).toBe(200);
    expect(plan.cappedFrom).toBe(500);
    expect(plan.notes.join(' ')).toMatch(/capped at .* 200 mm\/s/);
  });

  it('a picture too wide for the soft limits says how much room is missing and which pitch fits; it never clips', () => {
    const wide = textBitmap('HELLO WORLD, HELLO MAXL, HELLO AGAIN', 8);
    const r = planRaster(wide, settings, machine);
    expect(isProblem(r)).toBe(true);
    if (!isProblem(r)) return;
    expect(r.error).toMatch(/mm missing/);
    expect(r.fitPitch_mm).toBeGreaterThan(0);
    const fitted = planRaster(wide, { ...settings, pitch_mm: r.fitPitch_mm! }, machine);
    expect(isProblem(fitted)).toBe(false);
    if (!isProblem(fitted)) expect(fitted.layout.xEnd).toBeLessThanOrEqual(300);
  });

  it('an image too wide is never offered a pitch: its aspect is kept, so a finer pitch only adds columns', () => {
    // 2000 × 100 px at the strip's 8 × 6.4 mm: 1024 mm wide at any pitch. It was offered
    // “a pitch of 0.58 mm”, which made it 1765 columns and just as wide (and so on down).
    const image = { width: 512, height: 8, lit: new Uint8Array(512 * 8).fill(1) };
    const r = planRaster(image, { ...settings, widthFixed: true }, machine);
    expect(isProblem(r)).toBe(true);
    if (!isProblem(r)) return;
    expect(r.fitPitch_mm).toBeUndefined();
    expect(r.error).toMatch(/1024\.2 mm along x/);
    expect(r.error).toMatch(/crop the image/);
    expect(r.error).not.toMatch(/pitch of/);
  });

  it('refuses a machine without the bitmap channel, and bad settings', () => {
    expect(isProblem(planRaster(textBitmap('A', 8), settings, { ...machine, eventChannels: [] }))).toBe(true);
    expect(isProblem(planRaster(textBitmap('A', 8), { ...settings, pitch_mm: 0 }, machine))).toBe(true);
    expect(isProblem(planRaster(textBitmap('A', 8), { ...settings, speed: NaN }, machine))).toBe(true);
  });

  it('without colour and cruise channels it still paints, and says what it cannot do', () => {
    const plan = planRaster(textBitmap('A', 8), settings, { ...machine, eventChannels: ['neopixelBitmap'] }) as RasterPlan;
    expect(isProblem(plan)).toBe(false);
    expect(plan.notes.length).toBe(2);
  });
});
