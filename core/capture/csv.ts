/**
 * CSV export of a capture (d3-dsv), each sample joined with the plan at its
 * author time: the planned position of every motion axis, the planned velocity
 * and acceleration vectors, and the path speed and acceleration. Times are in
 * seconds from the first sample; the absolute author time is kept as well.
 */
import { csvFormat } from 'd3-dsv';
import type { TrajectorySample } from '../trajectory/tracks.ts';
import type { SensorCapture } from './sensorCapture.ts';

export interface CsvOptions {
  /** the trajectory, read at an author time */
  sample(t_us: number): TrajectorySample;
  motionAxes: readonly string[];
  /** names of the capture's channels, e.g. ['ax', 'ay', 'az'] */
  channelNames?: readonly string[];
}

export function captureToCsv(capture: SensorCapture, options: CsvOptions): string {
  const times = capture.timeColumn();
  const names = options.channelNames ?? Array.from({ length: capture.channels }, (_, c) => `${capture.reader}${c}`);
  const t0 = times.length > 0 ? times[0] : 0;
  const rows = Array.from(times, (t, k) => {
    const plan = options.sample(t);
    const row: Record<string, number> = { t_s: (t - t0) / 1e6, author_us: t };
    names.forEach((name, c) => (row[name] = capture.channel(c)[k]));
    options.motionAxes.forEach((axis, i) => {
      row[`planned_${axis}_mm`] = plan.position[i];
      row[`planned_v${axis}_mm_s`] = plan.velocity[i];
      row[`planned_a${axis}_mm_s2`] = plan.acceleration[i];
    });
    row.planned_speed_mm_s = plan.speed;
    row.planned_path_accel_mm_s2 = plan.pathAcceleration;
    return row;
  });
  const columns = [
    't_s',
    'author_us',
    ...names,
    ...options.motionAxes.flatMap((a) => [`planned_${a}_mm`, `planned_v${a}_mm_s`, `planned_a${a}_mm_s2`]),
    'planned_speed_mm_s',
    'planned_path_accel_mm_s2',
  ];
  return csvFormat(rows, columns);
}
