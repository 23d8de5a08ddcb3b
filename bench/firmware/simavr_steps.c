/*
 * Step-rate harness for bench/firmware.mjs, on libsimavr.
 *
 * Runs firmware/bench/StepRate (a MAXL_Device with one MAXL_Stepper, 80
 * steps/mm) on a simulated 16 MHz ATmega328P and, over its simulated UART at
 * 250 000 baud, opens a session, subscribes the stepper and queues a straight
 * move: accelerate at A to v = rate/80 mm/s, cruise CRUISE_MS ms in 6
 * segments (CRUISE_SEGMENTS, for a device whose queue holds fewer), decelerate. All frames arrive before the move starts (the link is
 * quiet during it, except for the device's own STATUS reports).
 *
 * Every rising edge of STEP (PD2) is stamped with the simulator's cycle count,
 * turned into the device's micros() through the sketch's calibration edge on
 * D8. The ideal time of step k is when the position, evaluated in double
 * precision from the very durations and f32 values that were sent (protocol
 * §5), crosses (k - 1/2) steps (the step generator's threshold). A step is
 * MISSED when it comes later than one step period (1 / step rate at that
 * moment) after its ideal time, earlier than 2 µs before it, or not at all.
 *
 * With STEPPERS=2 or 3 in the environment the sketch has that many steppers
 * (STEP D2/DIR D5, STEP D3/DIR D6, STEP D4/DIR D7: BlotPlotter's CoreXY pair,
 * the CncShield example's x, y, z), subscribed to slots 0, 1, 2 of the same
 * move. By default each slot moves as far as the path, so every motor steps at
 * RATE_HZ. With STEPPERS=2 and ANGLE_DEG=θ the move is a CoreXY line at θ to
 * x: motor a = x + y, motor b = x − y, so b moves (cos θ − sin θ)/(cos θ + sin θ)
 * as far as a (0.268 at 30°): a steps at RATE_HZ, b at its own lower rate,
 * and each is checked against its own period.
 *
 * Prints one JSON line: {"rate":..,"steps":..,"expected":..,"missed":..,...}
 * (steps and missed summed over the steppers; "perStepper" has each one's).
 *
 * Debugging: BENCH_DEBUG=1 prints segment starts, loops over 150 µs and every
 * late step; BENCH_PROFILE=FILE samples the program counter during the move
 * (bench/firmware/profile_symbols.py), only inside loops longer than N cycles
 * with BENCH_PROFILE_STALLS=N (1 600 if N is not given), only between
 * BENCH_PROFILE_FROM_US and BENCH_PROFILE_TO_US of device time if given.
 * BENCH_CALLS=ADDR,ADDR,... (byte addresses in hex, up to 16; see
 * bench/firmware/call_cycles.py, which takes function names) counts the calls
 * of those functions in the same span and the cycles each takes, callees
 * included and interrupts excluded (an interrupt vector's own cycles for a
 * vector), printed as "calls ADDR n cycles c" lines on stderr.
 *
 *   simavr_steps FILE.elf RATE_HZ [ACCEL_MM_S2 [CRUISE_MS]]
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <simavr/avr_ioport.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_core.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_irq.h>

#define STEPS_PER_MM 80.0
#define UNITS_PER_MM 65536.0
#define F_CPU 16000000.0
#define MAX_EDGES 400000
#define CRUISE_SEGMENTS 6  /* at most: 8 segments in all, the Uno queue holds 10 (CRUISE_SEGMENTS=N in the environment for fewer) */

static avr_t *avr;
#define MAX_STEPPERS 3
static uint64_t edges[MAX_STEPPERS][MAX_EDGES];
static int edgeCount[MAX_STEPPERS] = {0, 0, 0}, edgeOverflow = 0, dirChanges = 0, lastDir = -1;
static uint64_t calCycle = 0;
static int calMicrosKnown = 0;
static double calMicros = 0;
static char line[128];
static int lineLen = 0;
static uint8_t rxBytes[8192];
static int rxLen = 0;

/* ---------------------------------------------------------------- device output */
static void onUart(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  uint8_t b = (uint8_t)value;
  if (!calMicrosKnown) {
    if (b == '\n') {
      line[lineLen] = 0;
      if (strncmp(line, "CAL ", 4) == 0) { calMicros = atof(line + 4); calMicrosKnown = 1; }
      lineLen = 0;
    } else if (b != '\r' && lineLen < (int)sizeof line - 1) {
      line[lineLen++] = (char)b;
    }
    return;
  }
  if (rxLen < (int)sizeof rxBytes) rxBytes[rxLen++] = b;
}
static void onStep(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq;
  int m = (int)(intptr_t)param;
  if (!value) return;
  if (edgeCount[m] < MAX_EDGES) edges[m][edgeCount[m]++] = avr->cycle; else edgeOverflow = 1;
}
static void onDir(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if ((int)value != lastDir) { dirChanges++; lastDir = (int)value; }
}
static double deviceMicros(uint64_t cycle);
/* loop periods (D9 toggles once per loop) */
static uint64_t lastLoop = 0, loopCount = 0, loopCycles = 0, loopMax = 0;
static int measureLoops = 0;
static uint64_t loopHist[8]; /* <25, <30, <40, <50, <100, <200, <500, >=500 µs */
static void onLoop(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)value; (void)param;
  uint64_t c = avr->cycle;
  if (measureLoops && lastLoop) {
    uint64_t d = c - lastLoop;
    loopCount++;
    loopCycles += d;
    if (d > loopMax) loopMax = d;
    double us = d / 16.0;
    loopHist[us < 25 ? 0 : us < 30 ? 1 : us < 40 ? 2 : us < 50 ? 3 : us < 100 ? 4 : us < 200 ? 5 : us < 500 ? 6 : 7]++;
    if (getenv("BENCH_DEBUG") && us > 150) fprintf(stderr, "long loop: %.0f us ending at device time %.0f\n", us, deviceMicros(c));
  }
  lastLoop = c;
}
static void onCal(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if (value && !calCycle) calCycle = avr->cycle;
}

/* Device micros() (real-valued) at a simulator cycle: the calibration edge
 * comes ~4 cycles after Timer 0 ticked to the printed value. */
static double deviceMicros(uint64_t cycle) { return calMicros + ((double)cycle - (double)calCycle - 4.0) / 16.0; }

/* ---------------------------------------------------------------- author side */
static uint16_t crc16(const uint8_t *p, int n) {
  uint16_t crc = 0xFFFF;
  for (int i = 0; i < n; i++) {
    crc ^= (uint16_t)(p[i] << 8);
    for (int b = 0; b < 8; b++) crc = (crc & 0x8000) ? (uint16_t)((crc << 1) ^ 0x1021) : (uint16_t)(crc << 1);
  }
  return crc;
}
static uint8_t tx[4096];
static int txLen = 0;
static uint8_t seq = 0;
static void sendPacket(uint8_t type, const uint8_t *payload, int n) {
  uint8_t packet[70];
  int len = 0;
  packet[len++] = seq++;
  packet[len++] = type;
  memcpy(packet + len, payload, n);
  len += n;
  uint16_t crc = crc16(packet, len);
  packet[len++] = (uint8_t)crc;
  packet[len++] = (uint8_t)(crc >> 8);
  int codeAt = txLen++, code = 1; /* COBS */
  for (int i = 0; i < len; i++) {
    if (packet[i] == 0) { tx[codeAt] = (uint8_t)code; codeAt = txLen++; code = 1; }
    else { tx[txLen++] = packet[i]; code++; }
  }
  tx[codeAt] = (uint8_t)code;
  tx[txLen++] = 0;
}
static int putU16(uint8_t *p, uint32_t v) { p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); return 2; }
static int putU32(uint8_t *p, uint32_t v) { for (int i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (8 * i)); return 4; }
static int putF32(uint8_t *p, float f) { uint32_t v; memcpy(&v, &f, 4); return putU32(p, v); }
static int putVarint(uint8_t *p, uint32_t v) { int n = 0; while (v >= 0x80) { p[n++] = (uint8_t)(v | 0x80); v >>= 7; } p[n++] = (uint8_t)v; return n; }

/* ---------------------------------------------------------------- the move, as sent */
typedef struct {
  float length;      /* as sent (f32) */
  int32_t p0[MAX_STEPPERS], p1[MAX_STEPPERS];  /* units, per slot */
  uint8_t shape, phases;
  uint32_t d[3];
  float alpha;       /* as sent (f32) */
  double start;      /* device µs */
} Segment;
static Segment seg[CRUISE_SEGMENTS + 2];
static int segCount = 0;
static int steppers = 1;
static double scale[MAX_STEPPERS] = {1, 1, 1}; /* each slot's travel over the path's */

static int phaseSign(const Segment *s, int k) { int kind = (s->shape >> (2 * k)) & 3; return kind == 1 ? 1 : kind == 3 ? -1 : 0; }
static double duration(const Segment *s) { double t = 0; for (int k = 0; k < s->phases; k++) t += s->d[k]; return t; }

/* protocol §5 in double: σ and σ' (1/s) at τ µs into the segment */
static void sigmaAt(const Segment *s, double tauUs, double *sigma, double *nu) {
  double T = duration(s) * 1e-6, q = 0, rest = 0;
  for (int k = s->phases - 1; k >= 0; k--) { double d = s->d[k] * 1e-6; q += phaseSign(s, k) * d * (d / 2 + rest); rest += d; }
  double n = (1.0 - s->alpha * q) / T, sg = 0, tau = tauUs * 1e-6;
  if (tau < 0) tau = 0;
  if (tau > T) tau = T;
  for (int k = 0; k < s->phases; k++) {
    double d = s->d[k] * 1e-6, in = tau < d ? tau : d, a = phaseSign(s, k) * s->alpha;
    sg += in * (n + 0.5 * a * in);
    n += a * in;
    if (tau < d) break;
    tau -= d;
  }
  *sigma = sg;
  *nu = n;
}
/* slot m's position (units) and speed (mm/s) at device time t */
static void stateAt(int m, double t, double *pos, double *speed) {
  const Segment *s = &seg[0];
  for (int i = 0; i < segCount; i++) if (t >= seg[i].start) s = &seg[i];
  double sigma, nu;
  sigmaAt(s, t - s->start, &sigma, &nu);
  *pos = s->p0[m] + (double)(s->p1[m] - s->p0[m]) * sigma;
  *speed = fabs((double)(s->p1[m] - s->p0[m])) / UNITS_PER_MM * nu;
}

static void addSegment(double length, int shape, int phases, const double *seconds, double accel, double *at, double *start) {
  Segment *s = &seg[segCount++];
  s->length = (float)length;
  for (int m = 0; m < steppers; m++) {
    s->p0[m] = (int32_t)llround(*at * scale[m] * UNITS_PER_MM);
    s->p1[m] = (int32_t)llround((*at + length) * scale[m] * UNITS_PER_MM);
  }
  *at += length;
  s->shape = (uint8_t)shape;
  s->phases = (uint8_t)phases;
  for (int k = 0; k < phases; k++) s->d[k] = (uint32_t)llround(seconds[k] * 1e6);
  s->alpha = (float)(accel / length);
  s->start = *start;
  *start += duration(s);
}

int main(int argc, char **argv) {
  if (argc < 3) { fprintf(stderr, "usage: %s FILE.elf RATE_HZ [ACCEL [CRUISE_MS]]\n", argv[0]); return 2; }
  double rate = atof(argv[2]);
  double accel = argc > 3 ? atof(argv[3]) : 10000.0;
  double cruiseMs = argc > 4 ? atof(argv[4]) : 300.0;

  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(argv[1], &fw)) { fprintf(stderr, "cannot read %s\n", argv[1]); return 2; }
  avr = avr_make_mcu_by_name("atmega328p");
  if (!avr) { fprintf(stderr, "no atmega328p in simavr\n"); return 2; }
  avr_init(avr);
  avr->frequency = (uint32_t)F_CPU;
  avr->log = 0;
  avr_load_firmware(avr, &fw);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onUart, NULL);
  steppers = getenv("STEPPERS") ? atoi(getenv("STEPPERS")) : 1;
  if (steppers < 1 || steppers > MAX_STEPPERS) { fprintf(stderr, "STEPPERS must be 1..%d\n", MAX_STEPPERS); return 2; }
  if (getenv("ANGLE_DEG")) {
    double th = atof(getenv("ANGLE_DEG")) * M_PI / 180.0;
    if (steppers != 2 || cos(th) + sin(th) <= 0) { fprintf(stderr, "ANGLE_DEG needs STEPPERS=2 and a motor a moving forward\n"); return 2; }
    scale[1] = (cos(th) - sin(th)) / (cos(th) + sin(th));
  }
  for (int m = 0; m < steppers; m++) avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('D'), 2 + m), onStep, (void *)(intptr_t)m);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('D'), 5), onDir, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 0), onCal, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 1), onLoop, NULL);
  avr_irq_t *uartIn = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);

  /* boot and calibrate */
  while (!(calMicrosKnown && calCycle)) {
    int state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed || avr->cycle > 50 * F_CPU) { fprintf(stderr, "no calibration from the sketch\n"); return 1; }
  }

  /* the move: v = rate / 80 mm/s */
  double v = rate / STEPS_PER_MM;
  double tAcc = v / accel, dAcc = v * v / (2 * accel);
  int cruiseSegments = getenv("CRUISE_SEGMENTS") ? atoi(getenv("CRUISE_SEGMENTS")) : CRUISE_SEGMENTS;
  if (cruiseSegments < 1 || cruiseSegments > CRUISE_SEGMENTS) { fprintf(stderr, "CRUISE_SEGMENTS must be 1..%d\n", CRUISE_SEGMENTS); return 2; }
  double cruiseLen = v * cruiseMs * 1e-3 / cruiseSegments;
  double start = deviceMicros(avr->cycle) + 60000.0; /* frames take ~15 ms at 250 kbaud */
  double at = 0;
  double sec[3];
  sec[0] = tAcc; addSegment(dAcc, 0x01, 1, sec, accel, &at, &start);
  for (int i = 0; i < cruiseSegments; i++) { sec[0] = cruiseLen / v; addSegment(cruiseLen, 0x02, 1, sec, accel, &at, &start); }
  sec[0] = tAcc; addSegment(dAcc, 0x03, 1, sec, accel, &at, &start);
  double end = start;
  if (getenv("BENCH_DEBUG")) for (int i = 0; i < segCount; i++) fprintf(stderr, "segment %d starts at %.0f\n", i, seg[i].start);
  /* The planned speeds come from rounded durations: fix each alpha so that
   * consecutive segments join (σ' continuous) exactly as the author would. */

  uint8_t p[64];
  int n;
  p[0] = 1; sendPacket(0x01, p, 1);                               /* HELLO_REQUEST */
  for (int m = 0; m < steppers; m++) { p[0] = (uint8_t)m; p[1] = 1; p[2] = (uint8_t)m; sendPacket(0x04, p, 3); } /* SUBSCRIBE stepper m -> slot m */
  int perGeometry = (60 - 4 - 4 * steppers) / (4 + 4 * steppers); /* what fits a 60-byte payload */
  for (int first = 0; first < segCount; first += perGeometry) {  /* GEOMETRY */
    int count = segCount - first < perGeometry ? segCount - first : perGeometry;
    n = 0;
    n += putU16(p + n, (uint32_t)first); p[n++] = (uint8_t)count; p[n++] = first == 0 ? 1 : 0;
    if (first == 0) for (int m = 0; m < steppers; m++) n += putU32(p + n, 0);
    for (int i = first; i < first + count; i++) {
      n += putF32(p + n, seg[i].length);
      for (int m = 0; m < steppers; m++) n += putU32(p + n, (uint32_t)seg[i].p1[m]);
    }
    sendPacket(0x05, p, n);
  }
  for (int first = 0; first < segCount; first += 4) {            /* TIMING, 4 per frame */
    int count = segCount - first < 4 ? segCount - first : 4;
    n = 0;
    n += putU16(p + n, (uint32_t)first); p[n++] = (uint8_t)count; p[n++] = first == 0 ? 1 : 0;
    n += putF32(p + n, (float)accel);
    if (first == 0) n += putU32(p + n, (uint32_t)llround(seg[0].start));
    for (int i = first; i < first + count; i++) {
      p[n++] = seg[i].shape;
      for (int k = 0; k < seg[i].phases; k++) n += putVarint(p + n, seg[i].d[k]);
      n += putF32(p + n, seg[i].alpha);
    }
    sendPacket(0x06, p, n);
  }

  if (getenv("BENCH_DUMP")) { FILE *f = fopen(getenv("BENCH_DUMP"), "wb"); fwrite(tx, 1, txLen, f); fclose(f); }
  /* BENCH_PROFILE=FILE: sample the program counter every 97 cycles during the
   * move and write "address count" lines (byte addresses), for profiling. */
  const char *profilePath = getenv("BENCH_PROFILE");
  static uint32_t pcCount[16384];
  uint64_t nextSample = 0;
  /* BENCH_PROFILE_FROM_US / BENCH_PROFILE_TO_US: only samples in that span of device time */
  const double profileFrom = getenv("BENCH_PROFILE_FROM_US") ? atof(getenv("BENCH_PROFILE_FROM_US")) : 0.0;
  const double profileTo = getenv("BENCH_PROFILE_TO_US") ? atof(getenv("BENCH_PROFILE_TO_US")) : 1e300;
  /* BENCH_CALLS: a function is entered when the PC is at its address, and
   * left when the PC reaches the return address then on top of the stack with
   * the stack above where it was (an epilogue's two-byte SP writes make the SP
   * jump for an instruction: it alone does not tell a return). An interrupt
   * is entered when the PC is in the vector table and left likewise (the
   * vectors here do not nest); its cycles are taken out of every function it
   * interrupted. */
  int callFns = 0, callActive[16] = {0}, inIsr = 0;
  uint32_t callAddr[16], callRet[16], isrRet = 0;
  uint16_t callSp[16], isrSp = 0;
  uint64_t callStart[16], callIsrAtStart[16], callCycles[16] = {0}, callCount[16] = {0}, isrStart = 0, isrCycles = 0;
  if (getenv("BENCH_CALLS")) {
    char *list = strdup(getenv("BENCH_CALLS"));
    for (char *t = strtok(list, ","); t && callFns < 16; t = strtok(0, ",")) callAddr[callFns++] = (uint32_t)strtoul(t, 0, 16);
  }
  /* feed bytes at the line rate, then run to the end of the move */
  uint64_t nextByte = avr->cycle;
  int sent = 0;
  uint64_t stopCycle = 0;
  for (;;) {
    int state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed) { fprintf(stderr, "the AVR stopped (state %d)\n", state); return 1; }
    if (sent < txLen && avr->cycle >= nextByte) { avr_raise_irq(uartIn, tx[sent++]); nextByte = avr->cycle + 16 * 44; }
    if (!stopCycle && sent == txLen) stopCycle = calCycle + (uint64_t)((end + 50000.0 - calMicros) * 16.0);
    if (stopCycle && avr->cycle >= stopCycle) break;
    /* loop periods while the move runs (cruise and ramps) */
    measureLoops = sent == txLen && deviceMicros(avr->cycle) >= seg[0].start && deviceMicros(avr->cycle) < end;
    if (callFns && deviceMicros(avr->cycle) >= profileFrom && deviceMicros(avr->cycle) < profileTo) {
      uint16_t sp = _avr_sp_get(avr);
      /* the return address on top of the stack (pushed high byte first, in words) */
      uint32_t top = 2u * (((uint32_t)avr->data[sp + 1] << 8) | avr->data[sp + 2]);
      if (!inIsr && avr->pc < 0x68) { inIsr = 1; isrSp = sp; isrRet = top; isrStart = avr->cycle; }
      else if (inIsr && sp > isrSp && avr->pc == isrRet) { inIsr = 0; isrCycles += avr->cycle - isrStart; }
      for (int f = 0; f < callFns; f++) {
        if (!callActive[f] && avr->pc == callAddr[f]) {
          callActive[f] = 1 + inIsr;  /* 2: a vector's own code, nothing to take out */
          callSp[f] = sp; callRet[f] = top; callStart[f] = avr->cycle; callIsrAtStart[f] = isrCycles; callCount[f]++;
        } else if (callActive[f] && sp > callSp[f] && avr->pc == callRet[f]) {
          uint64_t c = avr->cycle - callStart[f];
          if (callActive[f] == 1) c -= isrCycles - callIsrAtStart[f];
          callCycles[f] += c;
          callActive[f] = 0;
        }
      }
    }
    if (profilePath && measureLoops && avr->cycle >= nextSample && deviceMicros(avr->cycle) >= profileFrom && deviceMicros(avr->cycle) < profileTo && (!getenv("BENCH_PROFILE_STALLS") || avr->cycle - lastLoop > (uint64_t)(atoi(getenv("BENCH_PROFILE_STALLS")) > 1 ? atoi(getenv("BENCH_PROFILE_STALLS")) : 1600))) { pcCount[(avr->pc >> 1) & 16383]++; nextSample = avr->cycle + 97; }
  }

  for (int f = 0; f < callFns; f++) fprintf(stderr, "calls %x %llu cycles %llu\n", callAddr[f], (unsigned long long)callCount[f], (unsigned long long)callCycles[f]);
  if (profilePath) { FILE *f = fopen(profilePath, "w"); for (int i = 0; i < 16384; i++) if (pcCount[i]) fprintf(f, "%d %u\n", i * 2, pcCount[i]); fclose(f); }
  /* answers: every frame must be acked */
  int acks = 0, nacks = 0, statuses = 0;
  { int start2 = 0;
    for (int i = 0; i < rxLen; i++) {
      if (rxBytes[i] != 0) continue;
      uint8_t dec[80]; int dn = 0, j = start2;
      while (j < i && dn < 70) { int code = rxBytes[j++]; for (int k = 1; k < code && j < i; k++) dec[dn++] = rxBytes[j++]; if (code < 0xFF && j < i) dec[dn++] = 0; }
      if (dn >= 4 && dec[1] == 0x43) { acks++; if (getenv("BENCH_DEBUG")) fprintf(stderr, "ACK seq %d\n", dec[2]); }
      if (dn >= 4 && dec[1] == 0x44) { nacks++; fprintf(stderr, "NACK seq %d reason %d detail %d\n", dec[2], dec[3], dec[4] | (dec[5] << 8)); }
      if (dn >= 4 && dec[1] == 0x46) statuses++;
      start2 = i + 1;
    } }

  /* compare every step with its ideal time */
  double stepUnits = UNITS_PER_MM / STEPS_PER_MM;
  long expectedAll = 0;
  int perMissed[MAX_STEPPERS] = {0, 0, 0};
  long perExpected[MAX_STEPPERS] = {0, 0, 0};
  int missed = 0, early = 0, late = 0;
  double maxLag = -1e9, minLag = 1e9, maxLagCruise = -1e9, worstRatio = 0;
  double cruiseStart = seg[1].start, cruiseEnd = seg[segCount - 1].start;
  int extra = 0, totalEdges = 0;
  for (int m = 0; m < steppers; m++) {
  long expected = (long)floor((double)seg[segCount - 1].p1[m] / stepUnits + 0.5);
  int missedBefore = missed + extra;
  perExpected[m] = expected;
  expectedAll += expected;
  totalEdges += edgeCount[m];
  if (edgeCount[m] > expected) extra += edgeCount[m] - (int)expected;
  for (long k = 1; k <= expected; k++) {
    double target = (k - 0.5) * stepUnits, lo = seg[0].start, hi = end;
    for (int it = 0; it < 60; it++) { double mid = 0.5 * (lo + hi), pos, sp; stateAt(m, mid, &pos, &sp); if (pos < target) lo = mid; else hi = mid; }
    double ideal = hi, pos, speed;
    stateAt(m, ideal, &pos, &speed);
    double period = speed > 1e-9 ? 1e6 / (speed * STEPS_PER_MM) : 1e12;
    if (k > edgeCount[m]) { missed++; continue; }
    double lag = deviceMicros(edges[m][k - 1]) - ideal;
    if (lag > maxLag) maxLag = lag;
    if (lag < minLag) minLag = lag;
    if (ideal >= cruiseStart && ideal < cruiseEnd && lag > maxLagCruise) maxLagCruise = lag;
    if (lag / period > worstRatio) worstRatio = lag / period;
    if (lag > period) { late++; missed++; if (getenv("BENCH_DEBUG")) fprintf(stderr, "late: stepper %d step %ld ideal %.1f lag %.1f\n", m, k, ideal, lag); }
    else if (lag < -2.0) { early++; missed++; }
  }
  perMissed[m] = missed + extra - missedBefore;
  }
  char perText[256];
  int perLen = 0;
  for (int m = 0; m < steppers; m++)
    perLen += snprintf(perText + perLen, sizeof perText - perLen, "%s{\"rateHz\":%.0f,\"steps\":%d,\"expected\":%ld,\"missed\":%d}",
                       m ? "," : "", rate * fabs(scale[m]), edgeCount[m], perExpected[m], perMissed[m]);
  printf("{\"rate\":%.0f,\"speedMmS\":%.3f,\"accelMmS2\":%.0f,\"steps\":%d,\"expected\":%ld,\"missed\":%d,\"late\":%d,\"early\":%d,"
         "\"maxLagUs\":%.2f,\"minLagUs\":%.2f,\"maxLagCruiseUs\":%.2f,\"worstLagOverPeriod\":%.3f,\"dirChanges\":%d,"
         "\"acks\":%d,\"nacks\":%d,\"statuses\":%d,\"edgeOverflow\":%d,"
         "\"perStepper\":[%s],\"loopMeanCycles\":%.1f,\"loopMaxCycles\":%llu,\"loopHistogramUs\":{\"<25\":%llu,\"<30\":%llu,\"<40\":%llu,\"<50\":%llu,\"<100\":%llu,\"<200\":%llu,\"<500\":%llu,\">=500\":%llu}}\n",
         rate, v, accel, totalEdges, expectedAll, missed + extra, late, early,
         maxLag, minLag, maxLagCruise, worstRatio, dirChanges, acks, nacks, statuses, edgeOverflow, perText,
         loopCount ? (double)loopCycles / loopCount : 0.0, (unsigned long long)loopMax,
         (unsigned long long)loopHist[0], (unsigned long long)loopHist[1], (unsigned long long)loopHist[2], (unsigned long long)loopHist[3],
         (unsigned long long)loopHist[4], (unsigned long long)loopHist[5], (unsigned long long)loopHist[6], (unsigned long long)loopHist[7]);
  return 0;
}
