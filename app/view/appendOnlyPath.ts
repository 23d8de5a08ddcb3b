/**
 * The locked (transmitted and historical) part of the trajectory: append-only
 * line segments in one Float32 buffer. New segments are written in place and
 * uploaded with an update range; the buffer only grows (by doubling) when full.
 *
 * Historical segments are always the oldest ones, so the one buffer is drawn by
 * two LineSegments objects sharing its attribute, with different draw ranges:
 * [0, historical) in the historical colour, [historical, count) in the
 * transmitted colour. Changing state is then a draw-range change, not a colour write.
 */
import * as THREE from 'three';
import { Bounds } from './bounds.ts';

const INITIAL_SEGMENTS = 65_536;

export class AppendOnlyPath {
  readonly historicalLines: THREE.LineSegments;
  readonly transmittedLines: THREE.LineSegments;
  readonly bounds = new Bounds();
  private attribute: THREE.BufferAttribute;
  private readonly historicalGeometry = new THREE.BufferGeometry();
  private readonly transmittedGeometry = new THREE.BufferGeometry();
  private count = 0;
  private historical = 0;

  constructor(historicalColor: string, transmittedColor: string) {
    this.attribute = this.makeAttribute(INITIAL_SEGMENTS);
    this.historicalLines = new THREE.LineSegments(this.historicalGeometry, new THREE.LineBasicMaterial({ color: historicalColor }));
    this.transmittedLines = new THREE.LineSegments(this.transmittedGeometry, new THREE.LineBasicMaterial({ color: transmittedColor }));
    for (const lines of [this.historicalLines, this.transmittedLines]) lines.frustumCulled = false;
    this.setRanges();
  }

  get segments(): number {
    return this.count;
  }

  get historicalSegments(): number {
    return this.historical;
  }

  clear(): void {
    this.count = 0;
    this.historical = 0;
    this.bounds.clear();
    this.setRanges();
  }

  /** Appends segments (2 vertices × xyz each) that start at segment index `from`. */
  append(from: number, vertices: Float32Array): void {
    const added = vertices.length / 6;
    if (added === 0) return;
    if (from !== this.count) {
      // A gap means a snapshot was missed: never happens in order, but keep the view honest.
      this.count = Math.min(from, this.count);
    }
    this.ensureCapacity(this.count + added);
    const array = this.attribute.array as Float32Array;
    const offset = this.count * 6;
    array.set(vertices, offset);
    this.attribute.addUpdateRange(offset, vertices.length);
    this.attribute.needsUpdate = true;
    this.bounds.addVertices(vertices);
    this.count += added;
    this.setRanges();
  }

  /** The transmitted (locked, not yet run) segments' vertices: 2 × xyz each (a view). */
  transmittedVertices(): Float32Array {
    return (this.attribute.array as Float32Array).subarray(this.historical * 6, this.count * 6);
  }

  /** mm of path in the transmitted segments. */
  transmittedLength(): number {
    const v = this.transmittedVertices();
    let total = 0;
    for (let i = 0; i < v.length; i += 6) total += Math.hypot(v[i + 3] - v[i], v[i + 4] - v[i + 1], v[i + 5] - v[i + 2]);
    return total;
  }

  setHistorical(n: number): void {
    const h = Math.min(n, this.count);
    if (h === this.historical) return;
    this.historical = h;
    this.setRanges();
  }

  private setRanges(): void {
    this.historicalGeometry.setDrawRange(0, this.historical * 2);
    this.transmittedGeometry.setDrawRange(this.historical * 2, (this.count - this.historical) * 2);
  }

  private makeAttribute(segments: number): THREE.BufferAttribute {
    const attribute = new THREE.BufferAttribute(new Float32Array(segments * 6), 3);
    attribute.setUsage(THREE.DynamicDrawUsage);
    this.historicalGeometry.setAttribute('position', attribute);
    this.transmittedGeometry.setAttribute('position', attribute);
    return attribute;
  }

  private ensureCapacity(segments: number): void {
    const capacity = this.attribute.array.length / 6;
    if (segments <= capacity) return;
    let next = capacity * 2;
    while (next < segments) next *= 2;
    const old = this.attribute;
    // Frees the old GPU buffer; the geometries are set up again at the next render.
    this.historicalGeometry.dispose();
    this.transmittedGeometry.dispose();
    const replacement = this.makeAttribute(next);
    (replacement.array as Float32Array).set((old.array as Float32Array).subarray(0, this.count * 6));
    this.attribute = replacement;
  }
}
