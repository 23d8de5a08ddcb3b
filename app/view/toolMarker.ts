/** A round marker of constant size on screen (the tool, the origin). */
import * as THREE from 'three';

let disc: THREE.Texture | null = null;

function discTexture(): THREE.Texture {
  if (disc) return disc;
  const size = 64;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const g = canvas.getContext('2d') as CanvasRenderingContext2D;
  g.fillStyle = '#fff';
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 2, 0, Math.PI * 2);
  g.fill();
  disc = new THREE.CanvasTexture(canvas);
  return disc;
}

export class ToolMarker {
  readonly points: THREE.Points;
  private readonly attribute: THREE.BufferAttribute;

  constructor(color: string, pixels: number) {
    const geometry = new THREE.BufferGeometry();
    this.attribute = new THREE.BufferAttribute(new Float32Array(3), 3).setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute('position', this.attribute);
    const material = new THREE.PointsMaterial({ color, size: pixels, sizeAttenuation: false, map: discTexture(), transparent: true, alphaTest: 0.5, depthTest: false });
    this.points = new THREE.Points(geometry, material);
    this.points.frustumCulled = false;
    this.points.renderOrder = 10;
  }

  moveTo(x: number, y: number, z: number): void {
    const a = this.attribute.array as Float32Array;
    if (a[0] === x && a[1] === y && a[2] === z) return;
    a[0] = x;
    a[1] = y;
    a[2] = z;
    this.attribute.needsUpdate = true;
  }
}
