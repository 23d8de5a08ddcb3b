/**
 * Sample loss detection: wrap-safe past the wire's u16 batch numbers, exact in batches
 * and in samples, duplicates dropped, and each gap reported once.
 */
import { describe, expect, it } from 'vitest';
import { ClockMap } from '../net/clockMap.ts';
import type { MessageOf } from '../net/messages.ts';
import { SensorCapture } from './sensorCapture.ts';

const PERIOD_US = 10_000;
const PER_BATCH = 3;
/** A device clock 1.5e9 µs ahead of the author's, 50 ppm fast (it wraps 2.8e9 µs in). */
const clock = new ClockMap(0, 1_500_000_000, 1.00005);

/** Batch n (unwrapped) of a reader that samples every 10 ms of its own clock, 3 samples a batch. */
function batch(n: number): { message: MessageOf<'SAMPLES'>; arrives_us: number } {
  const firstSample = n * PER_BATCH;
  const t0 = (clock.toDevice(0) + firstSample * PERIOD_US) % 0x1_0000_0000;
  return {
    message: {
      type: 'SAMPLES',
      reader: 0,
      sampleSeq: n & 0xffff,
      count: PER_BATCH,
      t0,
      samples: Array.from({ length: PER_BATCH }, (_, k) => ({ dt: k === 0 ? 0 : PERIOD_US, values: [firstSample + k] })),
    },
    arrives_us: (firstSample + PER_BATCH) * PERIOD_US + 3000,
  };
}

function feed(capture: SensorCapture, numbers: number[]) {
  return numbers.map((n) => {
    const b = batch(n);
    return capture.add(b.message, clock, b.arrives_us);
  });
}

describe('sample gaps', () => {
  it('finds no gap in an unbroken stream, across the u16 wrap of the batch number', () => {
    const capture = new SensorCapture('imu', 'accel', 1);
    const gaps = feed(capture, Array.from({ length: 70_000 }, (_, n) => 65_000 + n));
    expect(gaps.every((g) => g === null)).toBe(true);
    expect(capture.gaps).toEqual([]);
    expect(capture.size).toBe(70_000 * PER_BATCH);
    const seq = capture.sequenceColumn();
    expect(seq[seq.length - 1]).toBe(70_000 * PER_BATCH - 1);
    expect(capture.batchColumn()[capture.size - 1]).toBe(65_000 + 69_999);
  });

  for (const lost of [1, 2, 32_767, 32_768, 40_000, 65_535, 65_536, 65_537, 131_072]) {
    it(`counts a gap of ${lost} batches exactly, in batches and in samples`, () => {
      const capture = new SensorCapture('imu', 'accel', 1);
      const before = Array.from({ length: 20 }, (_, n) => 100 + n);
      const after = Array.from({ length: 5 }, (_, n) => 120 + lost + n);
      const gaps = feed(capture, [...before, ...after]);
      const reported = gaps.filter((g) => g !== null);
      expect(reported).toHaveLength(1);
      const gap = reported[0]!;
      expect(gap.kind).toBe('lost');
      expect(gap.batches).toBe(lost);
      expect(gap.samples).toBe(lost * PER_BATCH);
      expect(gap.index).toBe(20 * PER_BATCH);
      expect(gap.batch).toBe(120 + lost);
      expect(capture.lostBatches).toBe(lost);
      expect(capture.lostSamples).toBe(lost * PER_BATCH);
      // The sample numbers jump by exactly the samples lost, there and nowhere else.
      const seq = capture.sequenceColumn();
      for (let k = 1; k < seq.length; k++) expect(seq[k] - seq[k - 1]).toBe(k === gap.index ? lost * PER_BATCH + 1 : 1);
      // The sample number is the device's: the value each fake sample carries.
      const values = capture.channel(0);
      for (let k = 0; k < seq.length; k++) expect(seq[k] + 100 * PER_BATCH).toBe(values[k]);
    });
  }

  it('drops a duplicate batch and reports it, and also one repeated 65 536 batches later in number only', () => {
    const capture = new SensorCapture('imu', 'accel', 1);
    const gaps = feed(capture, [1, 2, 3, 3, 4, 2, 5]);
    expect(gaps.map((g) => g?.kind ?? null)).toEqual([null, null, null, 'duplicate', null, 'duplicate', null]);
    expect(capture.size).toBe(5 * PER_BATCH);
    expect(capture.duplicateBatches).toBe(2);
    expect(capture.lostSamples).toBe(0);
    const seq = capture.sequenceColumn();
    for (let k = 1; k < seq.length; k++) expect(seq[k] - seq[k - 1]).toBe(1);
  });

  it('a batch with the same u16 number, 65 536 batches on, is a gap of 65 535, not a duplicate', () => {
    const capture = new SensorCapture('imu', 'accel', 1);
    const gaps = feed(capture, [...Array.from({ length: 10 }, (_, n) => n), 9 + 65_536]);
    const gap = gaps[10]!;
    expect(gap.kind).toBe('lost');
    expect(gap.batches).toBe(65_535);
    expect(gap.samples).toBe(65_535 * PER_BATCH);
  });

  it('several gaps each give one report, in order', () => {
    const capture = new SensorCapture('imu', 'accel', 1);
    const numbers = Array.from({ length: 200 }, (_, n) => n).filter((n) => ![50, 51, 120, 121, 122, 190].includes(n));
    const gaps = feed(capture, numbers).filter((g) => g !== null);
    expect(gaps.map((g) => [g!.batches, g!.samples])).toEqual([
      [2, 6],
      [3, 9],
      [1, 3],
    ]);
    expect(capture.gaps).toHaveLength(3);
  });
});

describe('a device whose clock restarted', () => {
  it('counts the gap by the author clock when the device time across it makes no sense', () => {
    const capture = new SensorCapture('imu', 'accel', 1);
    feed(capture, Array.from({ length: 20 }, (_, n) => n));
    // The board rebooted: its batches start again at 0 and its clock near 0, 4 batches' time later.
    const restart = 24 * PER_BATCH * PERIOD_US;
    const gap = capture.add(
      { type: 'SAMPLES', reader: 0, sampleSeq: 0, count: 1, t0: 12_345, samples: [{ dt: 0, values: [0] }] },
      { toAuthor: () => restart } as unknown as ClockMap,
      restart + 3000,
    );
    expect(gap?.kind).toBe('lost');
    expect(gap?.restarted).toBe(true);
    // 130 ms from the last sample kept (at 590 ms) to this one: 12 samples between, 4 batches of 3.
    expect(gap?.samples).toBe(12);
    expect(gap?.batches).toBe(4);
  });
});
