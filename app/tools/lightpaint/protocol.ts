/**
 * The light-painting tool's messages (every one carries `tool: 'lightpaint'`).
 *
 *   page → worker   paint a bitmap; clear the photograph; send the exposure now
 *   worker → page   where the bitmap lies (or why it cannot run); the exposure,
 *                   a few times a second while it changes, as RGBA with its
 *                   buffer transferred
 */
import type { RasterLayout } from './raster.ts';

export interface PaintSettings {
  /** mm/s at cruise. */
  speed: number;
  /** mm per column along the move. */
  pitch_mm: number;
  /** '#rrggbb' */
  colour: string;
  /** 0..1 */
  brightness: number;
  gamma: number;
  reverse: boolean;
  /** The picture this many times side by side (1: once). */
  repeat: number;
  /** ms between evaluator samples. */
  evaluationPrecision_ms: number;
}

export interface PaintRequest {
  /** What the job panel calls it: “Text “HELLO”” */
  name: string;
  width: number;
  height: number;
  /** width × height, 1 lit, row 0 at the top; its buffer is transferred. */
  lit: Uint8Array;
  settings: PaintSettings;
  /** An image, its aspect kept: its width in mm does not change with the pitch (raster.ts RasterSettings.widthFixed). */
  widthFixed?: boolean;
}

export type LightpaintCommand =
  | { tool: 'lightpaint'; type: 'paint'; request: PaintRequest }
  /** A new photograph: the simulated exposure starts dark again. */
  | { tool: 'lightpaint'; type: 'clear-exposure' }
  /** Send the exposure now, tagged with `requestId` (to save it). */
  | { tool: 'lightpaint'; type: 'send-exposure'; requestId: number };

/** The exposure as an image: row 0 is the top (the largest y), as seen from above. */
export interface ExposureFrame {
  width: number;
  height: number;
  rgba: Uint8ClampedArray;
  mmPerPixel: number;
  /** mm, machine position of the bottom-left pixel's centre. */
  origin_mm: [number, number];
  /** Exposure (8-bit value × s) shown as 255: more saturates. */
  fullScale: number;
}

export type LightpaintEvent =
  | {
      tool: 'lightpaint';
      type: 'plan';
      layout: RasterLayout;
      /** mm, each LED's offset across the move from the tool, or null when the machine tells none (real boards). */
      ledOffsets_mm: number[] | null;
      speed: number;
      cappedFrom: number | null;
      notes: string[];
    }
  | { tool: 'lightpaint'; type: 'problem'; error: string; fitPitch_mm?: number }
  | ({ tool: 'lightpaint'; type: 'exposure'; requestId: number | null } & ExposureFrame)
  /** Whether the machine can show an exposure (a simulated LED strip), on every change of machine. */
  | { tool: 'lightpaint'; type: 'strip'; simulated: boolean; ledCount: number | null; ledSpacing_mm: number | null };
