/**
 * A saved capture's exports: its CSV (core/capture/csv.ts, so the same columns and the
 * same formula neutralisation as maxl.captureCsv) and the sidecar JSON beside it
 * (machine config, firmware versions, clock-sync error, the gaps, the analysis, and
 * the as-planned segments the planned columns were read from).
 */
import { captureCsvChunks, CSV_ROWS_PER_CHUNK, type CaptureColumns } from '../../../core/capture/csv.ts';
import type { TrajectorySample } from '../../../core/index.ts';
import type { CaptureRecord, SensorTrace } from './protocol.ts';

/** A sensor trace seen as a capture's columns. */
export function traceColumns(trace: SensorTrace): CaptureColumns {
  return {
    reader: trace.reader,
    channels: trace.values.length,
    gaps: trace.gaps,
    timeColumn: () => trace.author_us,
    deviceTimeColumn: () => trace.device_us,
    batchColumn: () => trace.batch,
    indexColumn: () => trace.index,
    sequenceColumn: () => trace.seq,
    channel: (c) => trace.values[c],
  };
}

/** The plan at sample k of a trace, as kept in the record (null where it was not known). */
export function plannedAt(trace: SensorTrace, k: number): TrajectorySample | null {
  const p = trace.planned;
  if (Number.isNaN(p.speed[k])) return null;
  return {
    position: p.position.map((a) => a[k]),
    actuator: [],
    velocity: p.velocity.map((a) => a[k]),
    acceleration: p.acceleration.map((a) => a[k]),
    speed: p.speed[k],
    pathAcceleration: p.pathAcceleration[k],
    distance: NaN,
    index: -1,
  };
}

/** A saved capture's CSV in pieces (core/capture/csv.ts captureCsvChunks): the header, then `rowsPerChunk` rows each. */
export function recordCsvChunks(record: CaptureRecord, sensor = 0, rowsPerChunk = CSV_ROWS_PER_CHUNK): Generator<string, void, void> {
  const trace = record.sensors[sensor];
  if (!trace) throw new RangeError(`the capture has no sensor ${sensor} (it has ${record.sensors.length})`);
  return captureCsvChunks(traceColumns(trace), { sample: (_t, k) => plannedAt(trace, k), motionAxes: record.axes, channelNames: trace.channelNames, start_us: record.start_us }, rowsPerChunk);
}

export function recordCsv(record: CaptureRecord, sensor = 0): string {
  return [...recordCsvChunks(record, sensor)].join('');
}

/** The sidecar: everything about the capture but its rows. */
export function recordSidecar(record: CaptureRecord, sensor = 0): Record<string, unknown> {
  const trace = record.sensors[sensor];
  const a = record.analysis;
  return {
    format: 'maxl-capture/1',
    csvColumns: 'see docs: t_s, author_us, device_us, batch, index_in_batch, sample_seq, lost_before, channels, planned_* per axis, planned_speed_mm_s, planned_path_accel_mm_s2',
    id: record.id,
    date: record.date,
    description: record.description,
    motion: record.motion,
    machine: record.machine,
    config: record.config,
    firmware: record.firmware,
    clockSyncError_us: record.syncError_us,
    sensor: trace ? { device: trace.device, reader: trace.reader, channels: trace.channelNames, samples: trace.author_us.length } : null,
    gaps: trace?.gaps ?? [],
    samplesLost: trace ? trace.gaps.reduce((n, g) => n + g.samples, 0) : 0,
    cutShort: record.cutShort,
    warnings: record.warnings,
    analysis: a
      ? { axis: a.axis, channel: a.channel, lag_ms: a.lag_ms, correlation: a.correlation, rms_mm_s2: a.rms_mm_s2, peak_hz: a.peak_hz, band_hz: a.band_hz, sampleRate_hz: a.sampleRate_hz }
      : null,
    window_us: [record.start_us, record.end_us],
    // Only on a simulated machine: its ground truth, to check the stamps and the peak by.
    simulatorTruth: record.simulatorTruth,
    // The as-planned segments over the capture (core/trajectory/history.ts records): the
    // planned columns are these evaluated at each sample's author_us.
    planSegments: record.segments,
  };
}

/** A file name for the capture's exports: date and motion, safe on every file system. */
export function recordFileStem(record: CaptureRecord): string {
  const date = record.date.replace(/[:.]/g, '-').replace(/Z$/, '');
  return `maxl-capture-${date}-${record.motion.kind}-${record.motion.axis}`.replace(/[^A-Za-z0-9._-]/g, '_');
}
