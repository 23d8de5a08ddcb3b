/**
 * USB frame arithmetic. Frames start at whole multiples of the frame period in
 * author time (the host controller's SOF clock is the host's clock, which is
 * the author's). Data that is ready at time t waits for the next frame start
 * strictly after t: a transfer cannot join a frame that has already begun.
 */
export function nextFrameStart(t_us: number, framePeriod_us: number): number {
  return (Math.floor(t_us / framePeriod_us) + 1) * framePeriod_us;
}
