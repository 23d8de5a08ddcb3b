/** The machine's work area (its soft limits) as a grid in the x-y plane, with an outline. */
import * as THREE from 'three';
import { SCENE_COLORS } from './colors.ts';

const DEFAULT_HALF_MM = 100;

export class WorkArea {
  readonly group = new THREE.Group();
  readonly box = new THREE.Box3();

  set(min: readonly number[], max: readonly number[]): void {
    for (const child of [...this.group.children]) {
      this.group.remove(child);
      const c = child as THREE.LineSegments;
      c.geometry.dispose();
      (c.material as THREE.Material).dispose();
    }
    const pick = (v: number | undefined, fallback: number) => (v !== undefined && Number.isFinite(v) ? v : fallback);
    const x0 = pick(min[0], -DEFAULT_HALF_MM), x1 = pick(max[0], DEFAULT_HALF_MM);
    if (min.length === 1) {
      this.rail(x0, x1);
      return;
    }
    const y0 = min.length > 1 ? pick(min[1], -DEFAULT_HALF_MM) : -10, y1 = max.length > 1 ? pick(max[1], DEFAULT_HALF_MM) : 10;
    this.box.set(new THREE.Vector3(x0, y0, 0), new THREE.Vector3(x1, y1, 0));
    const span = Math.max(x1 - x0, y1 - y0);
    const step = niceStep(span / 12);
    const grid: number[] = [];
    for (let x = Math.ceil(x0 / step) * step; x <= x1 + 1e-9; x += step) grid.push(x, y0, 0, x, y1, 0);
    for (let y = Math.ceil(y0 / step) * step; y <= y1 + 1e-9; y += step) grid.push(x0, y, 0, x1, y, 0);
    this.group.add(lines(grid, SCENE_COLORS.grid));
    this.group.add(lines([x0, y0, 0, x1, y0, 0, x1, y0, 0, x1, y1, 0, x1, y1, 0, x0, y1, 0, x0, y1, 0, x0, y0, 0], SCENE_COLORS.gridCenter));
  }

  private rail(x0: number, x1: number): void {
    const { rail, ticks, half } = railLines(x0, x1);
    this.box.set(new THREE.Vector3(x0, -half, 0), new THREE.Vector3(x1, half, 0));
    this.group.add(lines(ticks, SCENE_COLORS.grid));
    this.group.add(lines(rail, SCENE_COLORS.gridCenter));
  }
}

/** A one-axis machine's travel: a rail along x with ticks, not a plane. */
function railLines(x0: number, x1: number): { rail: number[]; ticks: number[]; half: number } {
  const step = niceStep((x1 - x0) / 12);
  const half = step / 4;
  const ticks: number[] = [];
  for (let x = Math.ceil(x0 / step) * step; x <= x1 + 1e-9; x += step) ticks.push(x, -half / 2, 0, x, half / 2, 0);
  // The ends of travel, taller.
  ticks.push(x0, -half, 0, x0, half, 0, x1, -half, 0, x1, half, 0);
  return { rail: [x0, 0, 0, x1, 0, 0], ticks, half };
}

function lines(values: number[], color: string): THREE.LineSegments {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(values, 3));
  const l = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color }));
  l.renderOrder = -1;
  return l;
}

/** 1, 2 or 5 times a power of ten, at least `raw`. */
function niceStep(raw: number): number {
  const p = Math.pow(10, Math.floor(Math.log10(Math.max(raw, 1e-6))));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}
