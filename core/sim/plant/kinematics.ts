/**
 * From motor positions to carriage (Cartesian) positions: the inverse of the
 * machine's transform.
 *
 * CoreXY (and H-bot) forward: a = x + y, b = x − y. Adding and subtracting:
 *   a + b = 2x  ⇒  x = (a + b)/2
 *   a − b = 2y  ⇒  y = (a − b)/2
 * Direct drive: each Cartesian axis is one motor.
 */
export type Kinematics =
  | { type: 'corexy'; a: string; b: string; x: string; y: string }
  | { type: 'direct'; axes: Record<string, string> }; // cartesian axis → motor

export function carriagePositions(k: Kinematics, motors: Readonly<Record<string, number>>): Record<string, number> {
  if (k.type === 'corexy') {
    const a = motors[k.a];
    const b = motors[k.b];
    return { [k.x]: (a + b) / 2, [k.y]: (a - b) / 2 };
  }
  const out: Record<string, number> = {};
  for (const [axis, motor] of Object.entries(k.axes)) out[axis] = motors[motor];
  return out;
}

/** The Cartesian axes a kinematics produces, in a fixed order. */
export function cartesianAxes(k: Kinematics): string[] {
  return k.type === 'corexy' ? [k.x, k.y] : Object.keys(k.axes);
}

/** The motors a kinematics reads. */
export function motorNames(k: Kinematics): string[] {
  return k.type === 'corexy' ? [k.a, k.b] : Object.values(k.axes);
}
