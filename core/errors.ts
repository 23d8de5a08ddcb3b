/**
 * Every error MAXL raises is a MaxlError with a stable `code`, so that apps can
 * branch on it, and a message a user can act on. `field` names the offending
 * config field or move property when there is one.
 */
export type MaxlErrorCode =
  | 'CONFIG_INVALID'
  | 'MOVE_INVALID'
  | 'MOVE_DIMENSION'
  | 'SOFT_LIMIT'
  | 'SEGMENT_LOCKED'
  | 'SEGMENT_NOT_FOUND'
  | 'QUEUE_CLOSED'
  | 'CANNOT_STOP_IN_PATH'
  | 'DEVICE_UNAVAILABLE'
  | 'VERSION_MISMATCH'
  | 'SUBSCRIPTION_MISMATCH'
  | 'LINK_LOST'
  | 'DEVICE_REFUSED'
  | 'BUFFER_CONFLICT'
  | 'NOT_STARTED'
  /** A recovery step called out of order (reconnect() before the machine stopped, resume() before reconnect()…). */
  | 'RECOVERY_ORDER';

export class MaxlError extends Error {
  readonly code: MaxlErrorCode;
  readonly field: string | undefined;

  constructor(code: MaxlErrorCode, message: string, field?: string) {
    super(field ? `${field}: ${message}` : message);
    this.name = 'MaxlError';
    this.code = code;
    this.field = field;
  }
}

/** Shorthand for the most common case: a config field that is wrong. */
export function configError(field: string, message: string): MaxlError {
  return new MaxlError('CONFIG_INVALID', message, field);
}
