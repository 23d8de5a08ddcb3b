/**
 * The shapes of a MAXL machine configuration, as an app writes it
 * (MaxlConfig), and as the core uses it once validated (ResolvedConfig).
 * Units: mm, s, mm/s, mm/s².
 *
 * Shapes only: this file imports nothing, so every part of the core can use them.
 */

export interface LimitsConfig {
  /** mm/s. A number bounds the magnitude of the velocity vector; an array bounds each motion axis. */
  maxVelocity?: number | number[];
  /** mm/s². A number bounds the magnitude of the acceleration vector; an array bounds each motion axis. */
  maxAcceleration?: number | number[];
  /** mm/s per motion axis, for giving per-axis limits beside a scalar maxVelocity. */
  axisMaxVelocity?: number[];
  /** mm/s² per motion axis, for giving per-axis limits beside a scalar maxAcceleration. */
  axisMaxAcceleration?: number[];
  /** mm. GRBL's junction deviation δ: how far a corner may be cut, in effect. Default 0.05. */
  junctionDeviation?: number;
}

/** CoreXY and H-bot share kinematics: a = x + y, b = x − y. */
export interface CoreXYTransform {
  type: 'corexy' | 'hbot';
  from: string[];
  to: string[];
}

/** Any linear map: to = matrix · from, with matrix[row = output][column = input]. */
export interface LinearTransform {
  type: 'linear';
  from: string[];
  to: string[];
  matrix: number[][];
}

/**
 * Any function of the inputs. Unless `linear` is true it is treated as nonlinear:
 * lines are subdivided so that the actuator path stays within `tolerance` (mm,
 * default 0.01) of the true image of the line.
 */
export interface FunctionTransform {
  type: 'function';
  from: string[];
  to: string[];
  fn: (input: readonly number[]) => number[];
  linear?: boolean;
  tolerance?: number;
}

export type TransformConfig = CoreXYTransform | LinearTransform | FunctionTransform;

/** A transform checked and ready to evaluate (config/transforms.ts). */
export interface ResolvedTransform {
  type: TransformConfig['type'];
  /** Indices of the input motion axes. */
  inputs: number[];
  /** Names of the output actuator axes. */
  outputs: string[];
  linear: boolean;
  /** Output units (mm for a motor on a belt). */
  tolerance: number;
  evaluate(input: readonly number[]): number[];
}

export interface SubscriptionConfig {
  /** The device's name, as its hello reports it. */
  device: string;
  /** A motion axis, an actuator axis, 'velocity', 'acceleration' or an event channel. */
  track: string;
  /** The reader's name inside the device. */
  reader: string;
}

export interface MaxlConfig {
  motionAxes: string[];
  eventChannels?: string[];
  limits: LimitsConfig;
  transforms?: TransformConfig[];
  subscriptions?: SubscriptionConfig[];
  /** mm, per motion axis: [min, max]. Moves that leave this box are refused. */
  softLimits?: Record<string, [number, number]>;
  /** Segments not yet transmitted that the queue holds before addSegmentToQueue waits; more while none of them is final yet (the lookahead needs a braking distance of path, up to 65 536 segments). Default 512. */
  queueCapacity?: number;
}

export type TrackKind = 'position' | 'velocity' | 'acceleration' | 'event';

export interface TrackInfo {
  name: string;
  kind: TrackKind;
  /** For position tracks: whether the track is a motion axis or a transform's output. */
  space?: 'motion' | 'actuator';
}

/** Limits checked and filled in (config/limits.ts). */
export interface ResolvedLimits {
  /** mm/s bound on |v|; Infinity when only per-axis limits were given. */
  maxSpeed: number;
  /** mm/s² bound on |a|; Infinity when only per-axis limits were given. */
  maxAccel: number;
  /** mm/s per axis; Infinity where unbounded. */
  axisMaxSpeed: number[];
  /** mm/s² per axis; Infinity where unbounded. */
  axisMaxAccel: number[];
  /** mm */
  junctionDeviation: number;
}

export interface ResolvedConfig {
  motionAxes: string[];
  eventChannels: string[];
  actuatorAxes: string[];
  tracks: TrackInfo[];
  limits: ResolvedLimits;
  transforms: ResolvedTransform[];
  subscriptions: SubscriptionConfig[];
  /** mm per motion axis; −∞/+∞ where unset. */
  softMin: number[];
  softMax: number[];
  queueCapacity: number;
}
