import { describe, expect, it } from 'vitest';
import { forwardingView } from './forwardingView.ts';
import { readOnlyQueue } from './queueView.ts';
import { TrajectoryQueue } from './queue.ts';
import { resolveConfig } from '../config/validate.ts';

interface Counter {
  readonly count: number;
  add(n: number): number;
}

class CounterWithMore implements Counter {
  count = 0;
  add(n: number): number {
    this.count += n;
    return this.count;
  }
  reset(): void {
    this.count = 0;
  }
}

describe('forwardingView', () => {
  it('forwards methods with the source as `this`, reads values live, and holds nothing else', () => {
    const source = new CounterWithMore();
    const face = forwardingView<Counter>(source, { count: 'value', add: 'method' });
    expect(face.add(2)).toBe(2);
    expect(source.count).toBe(2);
    source.count = 7;
    expect(face.count).toBe(7);
    expect(Object.keys(face).sort()).toEqual(['add', 'count']);
    expect('reset' in face).toBe(false);
  });

  it('cannot be assigned through', () => {
    const source = new CounterWithMore();
    const face = forwardingView<Counter>(source, { count: 'value', add: 'method' });
    expect(() => {
      (face as { count: number }).count = 3;
    }).toThrow(TypeError);
    expect(() => {
      (face as { add: unknown }).add = () => 0;
    }).toThrow(TypeError);
    expect(source.count).toBe(0);
  });

  it('takes only a plan that names every member with its kind (the type checker refuses the rest)', () => {
    const source = new CounterWithMore();
    // @ts-expect-error a value named as a method
    forwardingView<Counter>(source, { count: 'method', add: 'method' });
    // @ts-expect-error a member left out
    forwardingView<Counter>(source, { add: 'method' });
    // @ts-expect-error a member the interface lacks
    forwardingView<Counter>(source, { count: 'value', add: 'method', reset: 'method' });
  });

  it('readOnlyQueue gives exactly the QueueView members of a real queue, live', () => {
    const queue = new TrajectoryQueue(resolveConfig({ motionAxes: ['x', 'y'], limits: { maxVelocity: 100, maxAcceleration: 1000 } }));
    const view = readOnlyQueue(queue);
    expect(Object.keys(view).sort()).toEqual(
      ['capacity', 'get', 'hasRoom', 'segments', 'size', 'skippedZeroLength', 'subscribe', 'tailPosition', 'transmittedEnd_us', 'transmittedEndsMoving', 'untransmittedAt', 'untransmittedCount'].sort(),
    );
    const receipt = queue.append({ endPosition: [10, 0] });
    expect(view.size).toBe(1);
    expect(view.get(receipt.segmentIds[0])?.end).toEqual([10, 0]);
    expect(view.tailPosition).toEqual([10, 0]);
  });
});
