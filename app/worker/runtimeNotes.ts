/**
 * What the workbench tells the user, in the log, about an author that just became
 * ready and about gaps in sensor samples: words only, no state.
 */
import type { FeedLimit, SampleGap } from '../../core/index.ts';
import type { StreamerOptions } from '../../core/net/streamer.ts';
import type { LogLevel } from './protocol.ts';

export interface LogNote {
  level: LogLevel;
  code: string;
  message: string;
}

/**
 * Notes for a ready author: real boards' streaming margin (`streamer` is null on
 * a simulated machine), and a link so slow that it sets the shortest segment.
 */
export function readyNotes(streamer: Partial<StreamerOptions> | null, lead_us: number, limit: Readonly<FeedLimit> | null): LogNote[] {
  const notes: LogNote[] = [];
  if (streamer?.leadMargin_us !== undefined) {
    notes.push({
      level: 'info',
      code: 'MARGIN',
      message: `Real boards stream ${(streamer.leadMargin_us / 1000).toFixed(2)} ms of margin over twice the round trip (now ${(lead_us / 1000).toFixed(1)} ms of motion ahead).`,
    });
  }
  // Worth saying where it shapes real jobs (a UART's 25 kB/s: ~1.5 ms), not for native USB's ~30 µs.
  if (limit?.device && limit.minSegment_us >= 100) {
    notes.push({
      level: 'info',
      code: 'LINK',
      message: `${limit.device}'s link carries ${(limit.bytesPerSecond / 1000).toFixed(0)} kB/s, so every segment lasts at least ${(limit.minSegment_us / 1000).toFixed(2)} ms (${limit.bytesPerSegment.toFixed(0)} bytes each): short segments run slower than the limits allow.`,
    });
  }
  return notes;
}

/** A gap in a reader's sensor batches: samples lost, or a duplicate batch dropped. */
export function sampleGapNote(device: string, reader: string, g: SampleGap): LogNote {
  return g.kind === 'lost'
    ? {
        level: 'warning',
        code: 'SAMPLES_LOST',
        message: `${device}/${reader}: ${g.samples} samples lost (${g.batches} batches) between ${(g.from_us / 1e6).toFixed(3)} s and ${(g.to_us / 1e6).toFixed(3)} s`,
      }
    : { level: 'warning', code: 'SAMPLES_DUPLICATE', message: `${device}/${reader}: a duplicate batch (${g.droppedSamples} samples) was dropped` };
}
