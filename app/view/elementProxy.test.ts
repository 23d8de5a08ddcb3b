/**
 * three.js's own OrbitControls, on the element proxy the view worker gives it,
 * driven by replayed page events (no DOM here, as in the worker): a left drag pans
 * when LEFT is PAN (the top view) and orbits when it is ROTATE (3D), the wheel
 * zooms, and a released pointer ends the drag.
 */
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { describe, expect, it } from 'vitest';
import { ElementProxy } from './elementProxy.ts';
import type { ViewInputEvent } from './viewProtocol.ts';

function event(type: ViewInputEvent['type'], clientX: number, clientY: number, extra: Partial<ViewInputEvent> = {}): ViewInputEvent {
  return { type, pointerId: 1, pointerType: 'mouse', button: 0, clientX, clientY, pageX: clientX, pageY: clientY, ctrlKey: false, metaKey: false, shiftKey: false, deltaY: 0, deltaMode: 0, key: '', code: '', ...extra };
}

function setUp(left: THREE.MOUSE) {
  const element = new ElementProxy();
  element.place(100, 50, 800, 600);
  const camera = new THREE.PerspectiveCamera(35, 800 / 600, 0.1, 10_000);
  camera.position.set(0, 0, 500);
  const controls = new OrbitControls(camera, element as unknown as HTMLElement);
  controls.enableDamping = false;
  controls.screenSpacePanning = true;
  controls.mouseButtons.LEFT = left;
  controls.enableRotate = left === THREE.MOUSE.ROTATE;
  controls.update();
  let changes = 0;
  controls.addEventListener('change', () => changes++);
  const drag = (dx: number, dy: number) => {
    element.dispatch(event('pointerdown', 400, 300));
    for (let i = 1; i <= 4; i++) element.dispatch(event('pointermove', 400 + (dx * i) / 4, 300 + (dy * i) / 4));
    element.dispatch(event('pointerup', 400 + dx, 300 + dy));
  };
  return { element, camera, controls, drag, changes: () => changes };
}

describe('OrbitControls on the element proxy', () => {
  it('pans the top view with a left drag, still looking straight down', () => {
    const { camera, controls, drag, changes } = setUp(THREE.MOUSE.PAN);
    drag(120, 60);
    expect(changes()).toBeGreaterThan(0);
    expect(Math.hypot(controls.target.x, controls.target.y)).toBeGreaterThan(1);
    expect(camera.position.x).toBeCloseTo(controls.target.x, 6);
    expect(camera.position.y).toBeCloseTo(controls.target.y, 6);
    expect(camera.position.z - controls.target.z).toBeCloseTo(500, 6);
  });

  it('orbits in 3D with the same drag: the target stays, the camera turns', () => {
    const { camera, controls, drag } = setUp(THREE.MOUSE.ROTATE);
    drag(120, 60);
    expect(controls.target.length()).toBeCloseTo(0, 9);
    expect(camera.position.length()).toBeCloseTo(500, 6);
    expect(Math.hypot(camera.position.x, camera.position.y)).toBeGreaterThan(10);
  });

  it('zooms with the wheel, and a move after the release does nothing', () => {
    const { element, camera, controls } = setUp(THREE.MOUSE.PAN);
    element.dispatch(event('wheel', 500, 350, { deltaY: -100 }));
    const distance = camera.position.distanceTo(controls.target);
    expect(distance).toBeLessThan(500);
    element.dispatch(event('pointermove', 10, 10));
    expect(camera.position.distanceTo(controls.target)).toBe(distance);
    expect(controls.target.length()).toBe(0);
  });

  it('reports its place and size as a DOM element would', () => {
    const element = new ElementProxy();
    element.place(100, 50, 800, 600);
    expect(element.getBoundingClientRect()).toMatchObject({ left: 100, top: 50, right: 900, bottom: 650, width: 800, height: 600 });
    expect(element.ownerDocument).toBe(element);
  });
});
