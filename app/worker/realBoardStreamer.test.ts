import { describe, expect, it } from 'vitest';
import { DEFAULT_STREAMER } from '../../core/net/streamer.ts';
import { LINK_BURST_BYTES, realBoardStreamer } from './realBoardStreamer.ts';

describe('real boards’ streaming margins', () => {
  it('are the link’s burst plus the worker’s timer and task, and keep the lead ≤ 20 ms at USB round trips', () => {
    expect(LINK_BURST_BYTES).toBe(132);
    const uart = realBoardStreamer([{ bytesPerSecond: 25_000, bridged: false }, { bytesPerSecond: 1_216_000, bridged: false }]);
    // 132 bytes at 25 kB/s = 5.28 ms, + 4 ms timer clamp + 4 ms worker task
    expect(uart).toEqual({ leadMargin_us: 13_280, startMargin_us: 13_280, lagAllowance_us: 8_000, busyExcess_us: 100_000 });
    // The streamer's lead: max(minLead, 2·RTT + leadMargin), at a 3 ms USB round trip.
    const lead_us = Math.max(DEFAULT_STREAMER.minLead_us, 2 * 3_000 + (uart.leadMargin_us ?? NaN));
    expect(lead_us).toBeLessThanOrEqual(20_000);
  });

  it('keep the bridge’s 80 ms when one port’s bytes cross the page', () => {
    expect(realBoardStreamer([{ bytesPerSecond: 25_000, bridged: false }, { bytesPerSecond: 25_000, bridged: true }]).leadMargin_us).toBe(80_000);
  });
});
