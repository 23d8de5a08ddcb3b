/**
 * The shape an imported machine configuration needs before the Configure panel can
 * show it: every part the editor lists or edits is a container of the right kind
 * (motionAxes a list of names, limits an object, transforms a list of objects with
 * `from` and `to` lists, …). Values inside are not judged here: a negative speed or
 * an unknown axis name is imported, and configProblems.ts lists it before Apply, so
 * the user fixes it in the editor. A part of the wrong kind cannot be shown (the
 * editor would fail to draw), so the import refuses the file and names that part.
 */

/** The first part of `value` whose kind the editor cannot show, in words; null when every part can be shown. */
export function configShapeProblem(value: Record<string, unknown>): string | null {
  if (!isNames(value.motionAxes)) return '"motionAxes" must be a list of axis names';
  if (!isObject(value.limits)) return '"limits" must be an object (maxVelocity, maxAcceleration, …)';
  if (value.eventChannels !== undefined && !isNames(value.eventChannels)) return '"eventChannels" must be a list of channel names';
  if (value.subscriptions !== undefined) {
    if (!Array.isArray(value.subscriptions)) return '"subscriptions" must be a list';
    const at = value.subscriptions.findIndex((s) => !isObject(s));
    if (at >= 0) return `"subscriptions[${at}]" must be an object (device, reader, track)`;
  }
  if (value.transforms !== undefined) {
    if (!Array.isArray(value.transforms)) return '"transforms" must be a list';
    for (const [i, t] of value.transforms.entries()) {
      if (!isObject(t)) return `"transforms[${i}]" must be an object (type, from, to)`;
      if (!isNames(t.from)) return `"transforms[${i}].from" must be a list of motion axis names`;
      if (!isNames(t.to)) return `"transforms[${i}].to" must be a list of actuator axis names`;
    }
  }
  if (value.softLimits !== undefined) {
    if (!isObject(value.softLimits)) return '"softLimits" must be an object of [min, max] per axis';
    for (const [axis, range] of Object.entries(value.softLimits)) if (!Array.isArray(range)) return `"softLimits.${axis}" must be [min, max]`;
  }
  return null;
}

function isObject(v: unknown): v is Record<string, unknown> {
  return v !== null && typeof v === 'object' && !Array.isArray(v);
}

function isNames(v: unknown): v is string[] {
  return Array.isArray(v) && v.every((n) => typeof n === 'string');
}
