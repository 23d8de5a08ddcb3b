/**
 * createSimulatedMachine: a whole simulated machine from a preset, ready for
 * the runtime. Each device is a wasm instance of a real firmware example on
 * a simulated USB serial link; their pins drive one plant.
 *
 *   const sim = await createSimulatedMachine(lightPainter(), scheduler, { seed: 7, loader: nodeWasmLoader() });
 *   const maxl = createMAXL(sim.config);           // the runtime talks to sim.links[name]
 *   ...
 *   sim.sync();                                    // ground truth up to now
 *   sim.plant.leds?.image;                         // the light painting
 *   sim.cut('neopixel');                           // pull a cable
 *   sim.stop();
 *
 * Time comes from the scheduler: a VirtualScheduler in Node tests (fully
 * deterministic for a seed), a PacedScheduler in the browser.
 */
import type { MaxlConfig } from '../config/types.ts';
import type { Link } from '../net/link.ts';
import type { Scheduler } from '../time/scheduler.ts';
import { DeviceRunner } from './device/deviceRunner.ts';
import type { DeviceClockConfig } from './device/deviceClock.ts';
import { WasmDevice } from './device/wasmDevice.ts';
import type { WasmLoader } from './device/wasmLoader.ts';
import { SimError } from './errors.ts';
import type { LinkDirectionConfig, LinkOverrides } from './link/linkConfig.ts';
import { SimulatedLink, type LinkReport } from './link/simulatedLink.ts';
import { Plant } from './plant/plant.ts';
import type { MachinePreset } from './presets/presetTypes.ts';
import { deriveSeed } from '../random.ts';

export interface SimulatedMachineOptions {
  /** Seed of every random thing (link jitter and faults, sensor noise). Default 1. */
  seed?: number;
  /** Where firmware comes from: nodeWasmLoader() in Node, fetchWasmLoader() in a browser. */
  loader: WasmLoader;
  /** Link shaping per device name, over the preset's (a missing field keeps the preset's or the default). */
  links?: Record<string, LinkOverrides>;
  /** Clock per device name, over the preset's. */
  clocks?: Record<string, DeviceClockConfig>;
  /** Device loop period while busy and idle, µs, for every device (over the preset's). */
  loopPeriod_us?: number;
  idleTick_us?: number;
  /** The device runner's chunk, µs (default 1000, the USB frame). */
  chunk_us?: number;
  /** Keep each device's last N outputs (default 0). */
  outputLogSize?: number;
  /** Record the tool's true state every this many µs in plant.trace (default: the preset's, usually off). */
  toolTracePeriod_us?: number;
  /** Gets errors raised while devices run on the runner's timer (firmware traps). Default: thrown from the timer. */
  onError?: (error: unknown) => void;
}

export interface SimulatedMachine {
  readonly preset: MachinePreset;
  /** The MAXL config for the runtime (subscriptions name the firmware's devices and readers). */
  readonly config: MaxlConfig;
  /** The author's end of each device's link, by device name. */
  readonly links: Record<string, Link>;
  /** Each device's link model (counters, cut, faults), by device name. */
  readonly simLinks: Record<string, SimulatedLink>;
  /** Each device's wasm host (clock, counters, outputs, console), by device name. */
  readonly devices: Record<string, WasmDevice>;
  /** The physical side; read it after sync(). */
  readonly plant: Plant;
  /** Runs every device loop and the plant up to the scheduler's now (the runner otherwise catches up at its next chunk). */
  sync(): void;
  /** Cuts device `name`'s link at `at_us` (default now): nothing passes either way after it. */
  cut(name: string, at_us?: number): void;
  /** Reconnects a cut link from now on. */
  restore(name: string): void;
  /**
   * Restarts device `name` now, as its reset button would: a fresh instance of its
   * firmware (its RAM, queue and session gone; micros() from 0), on the same link,
   * pins and crystal. Its motors stop dead where they are.
   */
  reboot(name: string): Promise<void>;
  /** Makes device `name`'s µs counter jump by `delta_us` now (a clock fault). */
  jumpClock(name: string, delta_us: number): void;
  /** Changes one direction of a link's delays, jitter, corruption or loss from now on. */
  configureLink(name: string, direction: 'toDevice' | 'toAuthor', change: Partial<LinkDirectionConfig>): void;
  /** What every link did so far. */
  linkReports(): Record<string, LinkReport>;
  /** Stops the devices and closes the links. */
  stop(): Promise<void>;
}

export async function createSimulatedMachine(
  preset: MachinePreset,
  scheduler: Scheduler,
  options: SimulatedMachineOptions,
): Promise<SimulatedMachine> {
  const seed = options.seed ?? 1;
  const names = preset.devices.map((d) => d.name);
  if (new Set(names).size !== names.length) throw new SimError('SIM_CONFIG', `preset ${preset.id}: device names must be unique (${names.join(', ')})`);
  for (const name of Object.keys({ ...options.links, ...options.clocks })) {
    if (!names.includes(name)) throw new SimError('SIM_CONFIG', `preset ${preset.id} has no device "${name}" (devices: ${names.join(', ')})`);
  }

  const plantConfig = options.toolTracePeriod_us ? { ...preset.plant, toolTrace: { period_us: options.toolTracePeriod_us } } : preset.plant;
  const plant = new Plant(plantConfig, { seed, start_us: scheduler.now() });
  const modules = await Promise.all(preset.devices.map((d) => options.loader(d.example)));
  const simLinks: Record<string, SimulatedLink> = {};
  const devices: Record<string, WasmDevice> = {};
  const bootDevice = async (i: number, link: SimulatedLink): Promise<WasmDevice> => {
    const spec = preset.devices[i];
    const device = await WasmDevice.instantiate(modules[i], {
      name: spec.name,
      clock: options.clocks?.[spec.name] ?? spec.clock,
      hardware: plant.hardwareFor(spec.name),
      serialOut: (bytes, t) => link.device.send(bytes, t),
      loopPeriod_us: options.loopPeriod_us ?? spec.loopPeriod_us,
      idleTick_us: options.idleTick_us ?? spec.idleTick_us,
      outputLogSize: options.outputLogSize,
    });
    if (spec.firmwareName && spec.firmwareName !== spec.name) device.renameString(spec.firmwareName, spec.name);
    return device;
  };
  for (const [i, spec] of preset.devices.entries()) {
    const overrides = options.links?.[spec.name] ?? {};
    const link = new SimulatedLink(scheduler, `sim:${spec.name}`, {
      ...spec.link,
      ...overrides,
      toDevice: { ...spec.link?.toDevice, ...overrides.toDevice },
      toAuthor: { ...spec.link?.toAuthor, ...overrides.toAuthor },
      seed: overrides.seed ?? spec.link?.seed ?? deriveSeed(seed, `link/${spec.name}`),
    });
    simLinks[spec.name] = link;
    devices[spec.name] = await bootDevice(i, link);
  }
  const runner = new DeviceRunner(scheduler, Object.values(devices), options.chunk_us, options.onError);
  for (const [name, link] of Object.entries(simLinks)) link.device.onReceive((bytes) => runner.deliver(devices[name], bytes));
  runner.start();

  const linkOf = (name: string): SimulatedLink => {
    const link = simLinks[name];
    if (!link) throw new SimError('SIM_CONFIG', `no simulated device "${name}" (devices: ${names.join(', ')})`);
    return link;
  };
  const links: Record<string, Link> = {};
  for (const [name, l] of Object.entries(simLinks)) links[name] = l.link;

  return {
    preset,
    config: preset.config,
    links,
    simLinks,
    devices,
    plant,
    sync: () => {
      runner.runTo(scheduler.now());
      plant.advanceTo(scheduler.now());
    },
    cut: (name, at_us) => linkOf(name).cut(at_us),
    restore: (name) => linkOf(name).restore(),
    reboot: async (name) => {
      const link = linkOf(name);
      const old = devices[name];
      const next = await bootDevice(names.indexOf(name), link);
      // micros() counts from 0 again after a reset (an AVR keeps its count in RAM).
      next.clock.jump(-next.clock.deviceTimeAt(scheduler.now()));
      devices[name] = next;
      runner.replace(old, next);
    },
    jumpClock: (name, delta_us) => {
      linkOf(name);
      runner.runTo(scheduler.now());
      devices[name].clock.jump(delta_us);
    },
    configureLink: (name, direction, change) => linkOf(name).configure(direction, change),
    linkReports: () => Object.fromEntries(Object.entries(simLinks).map(([n, l]) => [n, l.report()])),
    stop: async () => {
      runner.stop();
      await Promise.all(Object.values(simLinks).map((l) => l.close()));
    },
  };
}
