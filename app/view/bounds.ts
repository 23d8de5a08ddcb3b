/** An axis-aligned box grown by points, for fit-to-view. */
import * as THREE from 'three';

export class Bounds {
  readonly box = new THREE.Box3();

  clear(): void {
    this.box.makeEmpty();
  }

  /** Adds vertices (x, y, z triples). */
  addVertices(v: Float32Array): void {
    const b = this.box;
    let minX = b.min.x, minY = b.min.y, minZ = b.min.z;
    let maxX = b.max.x, maxY = b.max.y, maxZ = b.max.z;
    for (let i = 0; i < v.length; i += 3) {
      const x = v[i], y = v[i + 1], z = v[i + 2];
      if (x < minX) minX = x;
      if (x > maxX) maxX = x;
      if (y < minY) minY = y;
      if (y > maxY) maxY = y;
      if (z < minZ) minZ = z;
      if (z > maxZ) maxZ = z;
    }
    b.min.set(minX, minY, minZ);
    b.max.set(maxX, maxY, maxZ);
  }
}
