/**
 * Seeded randomness for the simulator and benchmarks: the same seed gives the same
 * run. mulberry32 is a small, well-mixed 32-bit generator.
 */
export function seededRandom(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** A standard normal deviate from a uniform source (Box–Muller). */
export function gaussian(random: () => number): number {
  const u = Math.max(random(), 1e-300);
  return Math.sqrt(-2 * Math.log(u)) * Math.cos(2 * Math.PI * random());
}

/**
 * A seed for one named part of a simulation, from the simulation's seed: each
 * part (a link direction, a sensor's noise) gets its own independent stream, so
 * that traffic in one part does not shift the random numbers of another.
 * FNV-1a over the label, mixed with the seed through one mulberry32 step.
 */
export function deriveSeed(seed: number, label: string): number {
  let h = 0x811c9dc5;
  for (let i = 0; i < label.length; i++) {
    h ^= label.charCodeAt(i);
    h = Math.imul(h, 0x01000193);
  }
  return Math.floor(seededRandom((seed ^ h) >>> 0)() * 4294967296) >>> 0;
}
