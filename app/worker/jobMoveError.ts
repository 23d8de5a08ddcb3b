/**
 * A move of a job refused by the core, said in the job's own words: which move of
 * the job (counted from 1), where it comes from in the user's file when the tool
 * knows (`line 12 of plot.gcode`, `the <path> at line 7`), and what is wrong with it.
 * The core's batch calls name the move by its index in the array they were given
 * (`moves[3].maxVelocity`, core/errors.ts batchItemOf); a job may have handed the
 * core a slice, so the caller gives the job's own index.
 */
import { batchItemOf, MaxlError, ownMessage } from '../../core/index.ts';

/**
 * `err` (a move's error) as the error of the job's move `index` (0-based), with
 * `where` (the move's place in the user's file, if known) first: same code, the
 * field within the move kept in the words, no batch index left in them.
 */
export function jobMoveError(err: MaxlError, index: number, where: string | null): MaxlError {
  const field = batchItemOf(err)?.field ?? err.field ?? '';
  const place = where ? `${where} (move ${index + 1} of the job)` : `move ${index + 1} of the job`;
  return new MaxlError(err.code, `${place}: ${field ? `${field}: ` : ''}${ownMessage(err)}`);
}
