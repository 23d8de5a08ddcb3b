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
  /** streaming broke off for a reason of the author's own (not a device's): a bug, said plainly rather than thrown from a timer */
  | 'STREAM_FAILED'
  | 'NOT_STARTED'
  /** A wait was given up through its AbortSignal (addSegmentToQueue, whenIdle): nothing was changed by it. */
  | 'ABORTED'
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

/** The words of `err` without the field it names (MaxlError puts `field: ` before them). */
export function ownMessage(err: MaxlError): string {
  return err.field === undefined ? err.message : err.message.slice(err.field.length + 2);
}

/**
 * `err` as the error of one item of a batch: its field prefixed by `prefix`
 * (`moves[3]` and `endPosition` give `moves[3].endPosition`), same code and words.
 */
export function errorAt(err: MaxlError, prefix: string): MaxlError {
  return new MaxlError(err.code, ownMessage(err), err.field === undefined ? prefix : `${prefix}.${err.field}`);
}

/** Whether `err` refuses a move's content (rather than a wait: ABORTED, QUEUE_CLOSED). */
export function isMoveError(err: MaxlError): boolean {
  return err.code === 'MOVE_INVALID' || err.code === 'MOVE_DIMENSION' || err.code === 'SOFT_LIMIT';
}

/**
 * Which move of a batch `err` refuses, as its field names it (errorAt's `moves[i]…`,
 * as addSegmentsNow, addSegmentsToQueue and planPath throw it), and the field within
 * that move (`endPosition[1]`, `maxVelocity`; '' for the move itself); null when the
 * field names no batch item.
 */
export function batchItemOf(err: MaxlError): { index: number; field: string } | null {
  const m = /^moves\[(\d+)\]\.?(.*)$/.exec(err.field ?? '');
  return m ? { index: Number(m[1]), field: m[2] } : null;
}

/** Shorthand for the most common case: a config field that is wrong. */
export function configError(field: string, message: string): MaxlError {
  return new MaxlError('CONFIG_INVALID', message, field);
}

/** The MaxlError (code ABORTED) for a wait given up through `signal`: its reason in words, if it gave one. */
export function abortedError(signal: AbortSignal, what: string): MaxlError {
  const reason: unknown = signal.reason;
  const why = reason instanceof Error && reason.name !== 'AbortError' ? `: ${reason.message}` : typeof reason === 'string' ? `: ${reason}` : '';
  return new MaxlError('ABORTED', `${what} was aborted${why}`);
}

/**
 * `promise`, or a rejection with abortedError as soon as `signal` aborts (at once if
 * it already has). The work behind `promise` goes on; only this wait ends.
 */
export function abortable<T>(promise: Promise<T>, signal: AbortSignal | undefined, what: string): Promise<T> {
  if (!signal) return promise;
  if (signal.aborted) return Promise.reject(abortedError(signal, what));
  return new Promise<T>((resolve, reject) => {
    const onAbort = () => reject(abortedError(signal, what));
    signal.addEventListener('abort', onAbort, { once: true });
    promise.then(
      (value) => {
        signal.removeEventListener('abort', onAbort);
        resolve(value);
      },
      (err: unknown) => {
        signal.removeEventListener('abort', onAbort);
        reject(err);
      },
    );
  });
}
