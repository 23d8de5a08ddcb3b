/**
 * The MAXL core: the trajectory author. Pure TypeScript with no DOM; it runs in
 * Node, in a Web Worker or in a page.
 */
export { createMAXL, Maxl, type MaxlOptions, type WaitOptions } from './maxl.ts';
export {
  planPath,
  type PlannedPath,
  type PlannedSegment,
  type PathMove,
  type PathLine,
  type PathDwell,
  type PathSample,
  type PlanPathOptions,
} from './trajectory/planPath.ts';
export { batchItemOf, isMoveError, MaxlError, ownMessage, type MaxlErrorCode } from './errors.ts';
export { resolveConfig } from './config/validate.ts';
export type {
  MaxlConfig,
  LimitsConfig,
  TransformConfig,
  SubscriptionConfig,
  ResolvedConfig,
  TrackInfo,
  TrackKind,
} from './config/types.ts';
export type { Move, LinearMove, DwellMove } from './trajectory/moves.ts';
export { isDwell, MAX_DWELL_S, MIN_SPEED } from './trajectory/moves.ts';
export type { MoveEvents, EvaluatorState, EventEvaluatorSpec, EventTrack } from './trajectory/events.ts';
// The trajectory as apps read it (maxl.queue, maxl.history): read-only views. Maxl authors it.
export type { MoveReceipt } from './trajectory/queue.ts';
export type { QueueView, QueueViewEvent, QueueEventType, SegmentView, HistoryView } from './trajectory/queueView.ts';
export type { SegmentState } from './trajectory/segment.ts';
export type { TrajectorySample } from './trajectory/tracks.ts';
export { evaluateTiming, phasesOf, timingDuration, type Phase, type Timing } from './plan/phases.ts';

// The distributed runtime and what an app sees of it.
export type { Link } from './net/link.ts';
export { MAXL_DEFAULT_BAUD, uartBytesPerSecond, uartByteTime_us } from './net/link.ts';
export type { DeviceInfo, ReaderInfo, SessionOptions } from './net/session.ts';
export type { ReaderKindName } from './net/protocol.ts';
export type { DeviceReport, RecoveryReport, RuntimeEvent, StopRecord } from './runtime.ts';
export { bytesPerSegment, feedLimit, LINK_SHARE, type FeedLimit, type LinkLoad } from './net/linkFeedLimit.ts';
export type { StreamerOptions } from './net/streamer.ts';
export type { Scheduler, Timer } from './time/scheduler.ts';
export { VirtualScheduler } from './time/virtualScheduler.ts';
export { RealScheduler } from './time/realScheduler.ts';
export { PacedScheduler, type PacingStall } from './time/pacedScheduler.ts';
export { SensorCapture } from './capture/sensorCapture.ts';
export { captureToCsv, captureCsvColumns, type CaptureColumns } from './capture/csv.ts';
export { formatSafeCsv, safeCell } from './capture/csvSafe.ts';
export type { SampleGap } from './capture/sampleGaps.ts';
export { analyseCapture, type CaptureAnalysis } from './capture/analysis.ts';
export { amplitudeSpectrum, smoothSpectrum, spectrumPeak } from './capture/spectrum.ts';
export { crossCorrelationLag, rmsDifference } from './capture/lag.ts';
export { planTestMotion, limitsAlong, TestMotionError, type TestMotion } from './capture/testMotions.ts';
