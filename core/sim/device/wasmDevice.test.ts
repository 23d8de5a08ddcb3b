import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { VirtualScheduler } from '../../time/virtualScheduler.ts';
import { SimError } from '../errors.ts';
import { UNCONNECTED, type DeviceHardware } from './deviceHardware.ts';
import { DeviceRunner } from './deviceRunner.ts';
import { WasmDevice, type WasmDeviceOptions } from './wasmDevice.ts';

// The probe (testdata/probe.c) answers each byte with [byte, micros() u32 LE].
const probe = new WebAssembly.Module(readFileSync(new URL('./testdata/probe.wasm', import.meta.url)));

interface Sent {
  t: number;
  bytes: number[];
}

async function probeDevice(name: string, options: Partial<WasmDeviceOptions> = {}) {
  const sent: Sent[] = [];
  const device = await WasmDevice.instantiate(probe, {
    name,
    clock: { offset_us: 0, ppm: 0 },
    hardware: UNCONNECTED,
    serialOut: (bytes, t) => sent.push({ t, bytes: [...bytes] }),
    ...options,
  });
  return { device, sent };
}

const u32 = (b: number[], at: number) => (b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) | (b[at + 3] << 24)) >>> 0;

describe('WasmDevice', () => {
  it('gives the firmware micros() from its own clock: offset, drift and the 32-bit wrap', async () => {
    const s = new VirtualScheduler();
    const offset = 4294967296 - 1_000_000; // wraps one second in
    const { device, sent } = await probeDevice('p', { clock: { offset_us: offset, ppm: 250 }, idleTick_us: 100_000_000 });
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    for (const t of [500_000, 3_999_999, 600_000_000]) s.at(t, () => runner.deliver(device, Uint8Array.of(0x41)));
    await s.runUntil(700_000_000);
    expect(sent.map((x) => x.t)).toEqual([500_000, 3_999_999, 600_000_000]);
    for (const x of sent) {
      const want = Math.floor(offset + x.t * (1 + 250e-6)) % 4294967296;
      expect(u32(x.bytes, 1)).toBe(want);
    }
    expect(u32(sent[0].bytes, 1)).toBeGreaterThan(4_000_000_000); // before the wrap
    expect(u32(sent[1].bytes, 1)).toBeLessThan(4_000_000); // after it
  });

  it('loops at the idle tick while idle, at the loop period while busy, and at once on arrival', async () => {
    const s = new VirtualScheduler();
    const { device } = await probeDevice('p', { loopPeriod_us: 25, idleTick_us: 10_000 });
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    await s.runUntil(1_000_000);
    // Setup, then a loop at 0, 10 ms, …, 1 s.
    expect(device.counters.loops).toBe(101);
    expect(device.idle).toBe(true);
    // 'b' keeps it busy for 10 more loops at 25 µs.
    s.at(1_000_100, () => runner.deliver(device, new TextEncoder().encode('b')));
    await s.runUntil(1_000_100);
    expect(device.counters.loops).toBe(102);
    expect(device.idle).toBe(false);
    // Loops run in 1 ms chunks: by the chunk's end, all ten ran, each at its own time.
    await s.runUntil(1_000_999);
    expect(device.counters.loops).toBe(102);
    await s.runUntil(1_001_000);
    expect(device.counters.loops).toBe(112);
    expect(device.time_us).toBe(1_000_100 + 10 * 25);
    expect(device.idle).toBe(true);
    expect(device.nextLoop_us).toBe(1_000_100 + 10 * 25 + 10_000);
    // Timers: one per idle tick, and one per 1 ms chunk while busy, not one per loop.
    expect(runner.wakeups).toBeLessThanOrEqual(103);
  });

  it('keeps looping at the loop period while received bytes may still wait in the ring (32 per loop)', async () => {
    const s = new VirtualScheduler();
    const { device } = await probeDevice('p', { loopPeriod_us: 25, idleTick_us: 10_000 });
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    s.at(5000, () => runner.deliver(device, Uint8Array.of(0x2e)));
    await s.runUntil(5000);
    // One byte, read by the arrival loop: idle again at once.
    expect(device.busy).toBe(false);
    expect(device.nextLoop_us).toBe(15_000);
    s.at(20_000, () => runner.deliver(device, new Uint8Array(100).fill(0x2e)));
    await s.runUntil(21_000);
    // 100 bytes at up to 32 per loop: the arrival loop and 3 more at 25 µs, then the idle tick.
    expect(device.time_us).toBe(20_075);
    expect(device.nextLoop_us).toBe(30_075);
  });

  it('runs every device in one time order, so a loop never runs after a later arrival elsewhere', async () => {
    const s = new VirtualScheduler();
    const order: Array<[string, number]> = [];
    const hw = (name: string): DeviceHardware => ({ ...UNCONNECTED, digitalWrite: (_pin, _value, t) => order.push([name, t]) });
    const a = await probeDevice('a', { hardware: hw('a'), loopPeriod_us: 20 });
    const b = await probeDevice('b', { hardware: hw('b'), loopPeriod_us: 20 });
    const runner = new DeviceRunner(s, [a.device, b.device]);
    runner.start();
    // 's' steps at the arrival; 'b' makes ten busy loops, each writing a pin: both devices loop inside the same chunks.
    const bytes = new TextEncoder().encode('sb');
    for (let k = 0; k < 50; k++) {
      s.at(1000 + k * 317, () => runner.deliver(a.device, bytes));
      s.at(1100 + k * 211, () => runner.deliver(b.device, bytes));
    }
    await s.runUntil(100_000);
    expect(order.length).toBeGreaterThan(300);
    for (let i = 1; i < order.length; i++) expect(order[i][1]).toBeGreaterThanOrEqual(order[i - 1][1]);
    expect(order.filter(([n]) => n === 'a').map(([, t]) => t)).toContain(1000 + 7 * 317);
  });

  it('forwards pins, LEDs, servo pulses and I2C to the hardware with their times, and logs outputs', async () => {
    const s = new VirtualScheduler();
    const calls: string[] = [];
    const hardware: DeviceHardware = {
      ...UNCONNECTED,
      digitalWrite: (pin, v, t) => calls.push(`dw ${pin}=${v} @${t}`),
      ledShow: (pin, rgb, t) => calls.push(`led ${pin} [${[...rgb]}] @${t}`),
      servoPulse: (pin, us, t) => calls.push(`servo ${pin} ${us} @${t}`),
      i2cWrite: (addr, data, t) => (calls.push(`i2cw ${addr} [${[...data]}] @${t}`), 0),
      i2cRead: (addr, n, t) => (calls.push(`i2cr ${addr} ${n} @${t}`), Uint8Array.of(0xa0)),
    };
    const { device, sent } = await probeDevice('p', { hardware, outputLogSize: 100 });
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    s.at(5000, () => runner.deliver(device, new TextEncoder().encode('slpi')));
    await s.runUntil(10_000);
    expect(calls).toEqual([
      'dw 5=1 @5000',
      'dw 2=1 @5000',
      'dw 2=0 @5000',
      'led 6 [1,2,3,4,5,6] @5000',
      'servo 9 1500 @5000',
      'i2cw 40 [0] @5000',
      'i2cr 40 1 @5000',
    ]);
    // One serial write for the whole loop: four 5-byte answers; 'i' answers the register read.
    expect(sent).toHaveLength(1);
    expect(sent[0].bytes.length).toBe(20);
    expect(sent[0].bytes[15]).toBe('i'.charCodeAt(0));
    expect(sent[0].bytes[16]).toBe(0xa0);
    expect(device.outputs.map((o) => o.kind)).toEqual(['pinMode', 'pinMode', 'digital', 'digital', 'digital', 'led', 'servo', 'i2cWrite', 'i2cRead', 'serial']);
    expect(device.counters.digitalWrites).toBe(3);
  });

  it('counts bytes lost when the firmware’s receive ring overflows', async () => {
    const s = new VirtualScheduler();
    const { device, sent } = await probeDevice('p');
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    s.at(100, () => runner.deliver(device, new Uint8Array(3000).fill(0x2e)));
    await s.runUntil(1000);
    expect(device.counters.bytesReceived).toBe(2048);
    expect(device.counters.bytesOverrun).toBe(952);
    expect(sent[0].bytes.length).toBe(5 * 2048);
  });

  it('turns a firmware trap into a DEVICE_TRAP error and stops running that device', async () => {
    const s = new VirtualScheduler();
    const { device } = await probeDevice('p');
    const errors: unknown[] = [];
    const runner = new DeviceRunner(s, [device], 1000, (e) => errors.push(e));
    runner.start();
    s.at(2000, () => runner.deliver(device, new TextEncoder().encode('t')));
    await s.runUntil(100_000);
    expect(errors).toHaveLength(1);
    expect(errors[0]).toBeInstanceOf(SimError);
    expect((errors[0] as SimError).code).toBe('DEVICE_TRAP');
    expect(device.crashed).toBe(errors[0]);
    const loops = device.counters.loops;
    await s.runUntil(200_000);
    expect(device.counters.loops).toBe(loops);
  });

  it('renames a string in the firmware, as if the sketch were edited and reflashed', async () => {
    const s = new VirtualScheduler();
    const { device, sent } = await probeDevice('p');
    expect(() => device.renameString('probeDevice', 'muchTooLongName')).toThrow(SimError);
    expect(() => device.renameString('nowhere', 'x')).toThrow(/0 times/);
    device.renameString('probeDevice', 'probeB');
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    s.at(10, () => runner.deliver(device, new TextEncoder().encode('n')));
    await s.runUntil(1000);
    expect(new TextDecoder().decode(Uint8Array.from(sent[0].bytes))).toBe('nprobeB\0');
  });

  it('lets time pass while the firmware busy-waits on micros(), as delay() does', async () => {
    const s = new VirtualScheduler();
    const stamps: number[] = [];
    const hardware: DeviceHardware = { ...UNCONNECTED, digitalWrite: (_p, _v, t) => stamps.push(t) };
    const { device, sent } = await probeDevice('p', { hardware, busyWaitAfterCalls: 100, busyWaitStep_us: 2 });
    const runner = new DeviceRunner(s, [device]);
    runner.start();
    // 'w' spins until micros() has advanced 5000 µs, then steps: 100 free reads, then 2 µs per read.
    s.at(10_000, () => runner.deliver(device, new TextEncoder().encode('wA')));
    await s.runUntil(20_000);
    expect(stamps[0]).toBeGreaterThanOrEqual(15_000);
    expect(stamps[0]).toBeLessThan(15_010);
    // 'w' was answered with the clock before the wait, 'A' with the clock after it.
    expect(sent).toHaveLength(1);
    expect(u32(sent[0].bytes, 1)).toBe(10_000);
    expect(u32(sent[0].bytes, 6)).toBeGreaterThanOrEqual(15_000);
    expect(u32(sent[0].bytes, 6)).toBeLessThan(15_010);
    expect(device.time_us).toBeGreaterThanOrEqual(15_000);
    expect(device.nextLoop_us).toBeGreaterThan(15_000);
  });

  it('refuses modules that import what the ABI does not provide, or lack its exports', async () => {
    // (module (import "env" "bogus" (func)))
    const bogus = new WebAssembly.Module(
      Uint8Array.of(0, 0x61, 0x73, 0x6d, 1, 0, 0, 0, 1, 4, 1, 0x60, 0, 0, 2, 13, 1, 3, 0x65, 0x6e, 0x76, 5, 0x62, 0x6f, 0x67, 0x75, 0x73, 0, 0),
    );
    const options = { name: 'x', clock: { offset_us: 0, ppm: 0 }, hardware: UNCONNECTED, serialOut: () => {} };
    await expect(WasmDevice.instantiate(bogus, options)).rejects.toMatchObject({ code: 'WASM_ABI', message: expect.stringContaining('env.bogus') });
    const empty = new WebAssembly.Module(Uint8Array.of(0, 0x61, 0x73, 0x6d, 1, 0, 0, 0));
    await expect(WasmDevice.instantiate(empty, options)).rejects.toMatchObject({ code: 'WASM_ABI' });
  });
});
