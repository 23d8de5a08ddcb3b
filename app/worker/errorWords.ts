/**
 * Errors in words a user can act on. The core's MaxlError messages already say
 * what happened; this adds, per code, where in the workbench to fix it.
 */
import { MaxlError } from '../../core/index.ts';

const WHAT_TO_DO: Partial<Record<string, string>> = {
  SUBSCRIPTION_MISMATCH: 'Open Configure → Subscriptions: each connection drawn in red says what is wrong with it.',
  CONFIG_INVALID: 'Fix the field named above in Configure; nothing runs until the configuration is valid.',
  DEVICE_UNAVAILABLE: 'Check that the board runs a MAXL firmware example and is plugged in, then add it again.',
  VERSION_MISMATCH: 'Flash the firmware that matches this workbench, or open the workbench that matches the firmware.',
  LINK_LOST: 'Check the USB cable and the board’s power; the machine was brought to rest on the path. When it is back, press Resume to finish the job, or Re-arm to drop it.',
  RECOVERY_ORDER: 'The machine stopped off its plan: press Resume to reconnect and finish the job from where it stopped, or Re-arm to drop it.',
  BUFFER_CONFLICT: 'Lower the job’s speed or join its tiny segments into longer ones, then run it again.',
  SOFT_LIMIT: 'Jog or set the job inside the soft limits, or widen them in Configure → Axes.',
  DEVICE_REFUSED: 'If a segment came late, the computer or the link was too slow: close busy tabs or use a shorter USB cable, then run again.',
  STREAM_FAILED: 'The machine was brought to rest on the path. This is a fault of the workbench itself: please report it with this log, then press Re-arm.',
  NOT_STARTED: 'The machine is not streaming yet: wait for “ready”, or fix the problem shown above the view.',
};

export interface ErrorWords {
  code: string;
  message: string;
}

/** The code and a message (with what to do) for anything thrown. */
export function errorWords(err: unknown): ErrorWords {
  if (err instanceof MaxlError) {
    const hint = WHAT_TO_DO[err.code];
    return { code: err.code, message: hint ? `${err.message}\n${hint}` : err.message };
  }
  if (err instanceof Error) {
    const code = (err as Error & { code?: unknown }).code;
    return { code: typeof code === 'string' ? code : err.name || 'ERROR', message: err.message };
  }
  return { code: 'ERROR', message: String(err) };
}
