/**
 * Helpers for simulator tests that drive firmware by hand (no runtime): open a
 * session, subscribe readers, and send one constant-speed segment, with times
 * converted to the device's clock from the simulator's ground truth (the
 * runtime estimates that mapping instead).
 */
import { PROTOCOL_VERSION, ReaderKind, type ReaderKindName } from '../../net/protocol.ts';
import type { Scheduler } from '../../time/scheduler.ts';
import type { SimulatedMachine } from '../machine.ts';
import { FrameClient } from './frameClient.ts';

export const MM = 65536; // wire position units per mm

export class DeviceDriver {
  readonly client: FrameClient;
  private seq = 0;

  constructor(
    private readonly scheduler: Scheduler,
    private readonly sim: SimulatedMachine,
    readonly device: string,
  ) {
    this.client = new FrameClient(scheduler, sim.links[device]);
  }

  /** Device µs (u32) at author time t. */
  deviceTime(t_us: number): number {
    return this.sim.devices[this.device].clock.microsAt(t_us);
  }

  /** Author time of a device time seen recently (within half a wrap of `near_us`). */
  authorTime(device_us: number, near_us: number): number {
    const clock = this.sim.devices[this.device].clock;
    const near = clock.deviceTimeAt(near_us);
    let d = device_us - (near % 4294967296);
    if (d > 2147483648) d -= 4294967296;
    if (d < -2147483648) d += 4294967296;
    return clock.authorTimeAt(near + d);
  }

  hello(): void {
    this.seq = 0;
    this.client.send(this.seq++, { type: 'HELLO_REQUEST', protocol: PROTOCOL_VERSION });
  }

  subscribe(reader: number, kind: ReaderKindName, slot: number): void {
    this.client.send(this.seq++, { type: 'SUBSCRIBE', reader, kind: ReaderKind[kind], slot });
  }

  /**
   * One segment from p0 to p1 (mm per position slot; [] for a device with no
   * position reader) of `length` mm at constant speed, starting at author time
   * `start_us` and lasting `duration_us` (device µs ≈ author µs).
   */
  cruise(id: number, p0: number[], p1: number[], length: number, start_us: number, duration_us: number): void {
    this.client.send(this.seq++, {
      type: 'GEOMETRY',
      firstId: id,
      count: 1,
      flags: 1,
      p0: p0.map((p) => Math.round(p * MM)),
      segments: [{ length, p1: p1.map((p) => Math.round(p * MM)) }],
    });
    this.client.send(this.seq++, {
      type: 'TIMING',
      firstId: id,
      count: 1,
      flags: 1,
      stopDecel: 1000,
      start: this.deviceTime(start_us),
      segments: [{ shape: 2, durations: [duration_us], alpha: 0 }],
    });
  }

  /** Event changes inside segment `id`, at device µs offsets from its start. */
  events(id: number, slot: number, entries: Array<{ offset: number; value: number }>): void {
    this.client.send(this.seq++, { type: 'EVENTS', segmentId: id, slot, firstIndex: 0, count: entries.length, entries });
  }

  nacks(): unknown[] {
    return this.client.of('NACK').map((n) => n.message);
  }
}
