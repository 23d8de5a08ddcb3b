/**
 * A read-only face of an object: a new object that forwards a chosen interface's
 * members to the source and holds nothing else, so that whoever is given the face
 * reaches neither the source's other members nor a way to change them
 * (queueView.ts: `maxl.queue`, `maxl.history`).
 *
 * The plan names every member of the interface once, as 'method' (called on the
 * source, looked up at each call) or 'value' (read from the source at each access:
 * a getter, so the face always shows the source as it is now). The plan's type
 * requires every member of T and checks each one's kind, so a member added to the
 * interface and not to the plan is a type error, not a member missing at run time.
 * The face's properties cannot be assigned or redefined.
 */

/** Whether a member of T is a method (called on the source) or a value (read from it). */
export type ForwardPlan<T> = {
  readonly [K in keyof T]-?: T[K] extends (...args: never[]) => unknown ? 'method' : 'value';
};

export function forwardingView<T extends object>(source: T, plan: ForwardPlan<T>): T {
  const face = {};
  for (const key of Object.keys(plan) as Array<keyof T & string>) {
    const descriptor: PropertyDescriptor =
      plan[key] === 'method'
        ? { value: (...args: unknown[]) => Reflect.apply(source[key] as (...a: unknown[]) => unknown, source, args) }
        : { get: () => source[key] };
    Object.defineProperty(face, key, { ...descriptor, enumerable: true });
  }
  // Every member of T is defined above: ForwardPlan<T> names each one, with its kind.
  return face as T;
}
