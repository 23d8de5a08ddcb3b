/*
 * Hardware in the loop: an Arduino Uno (ATmega328P at 16 MHz, simulated by
 * libsimavr cycle by cycle) running a real sketch's ELF, its UART0 on a
 * pseudo-terminal at the wire's own pace, in real time, with its STEP/DIR pin
 * edges stamped. The Node core opens the pty with `serialport` as it would a
 * board's /dev/ttyACM0 (core/system/hil.test.ts).
 *
 *   simavr_uno_pty FILE.elf [--baud B] [--step-pin N] [--dir-pin N]
 *                  [--overflow-count ADDR] [--seconds S] [--lockstep 1]
 *
 * Lockstep (--lockstep 1): the AVR runs only as far as the driver allows. It
 * reads lines "G <cycle>" on stdin (run until that cycle), and prints
 * "C <cycle>" each time it gets there, then waits for the next grant ("Q" or
 * end of input quits). The driver (core/system/hil/unoBoard.ts) moves its
 * author's clock to that cycle before granting the next few hundred µs, so the
 * two clocks advance together whatever the host's load (see "Real time" below).
 * Bytes keep causality: what the sketch transmits in a quantum reaches the pty
 * once the next grant came (the author's clock is then past it), and what the
 * author wrote before a grant enters the UART after it; either way a byte is
 * late by up to a quantum, never early.
 *
 * Prints, one line each, flushed at least every 5 ms of real time:
 *   PTY <path>              the pty's slave, once, before the AVR starts
 *   T0 <ns>                 CLOCK_MONOTONIC ns at cycle 0 (the Node side uses the same
 *                           clock: process.hrtime.bigint())
 *   MICROS0 <cycle>         the cycle at which the sketch's micros() read 0 (from
 *                           timer0_overflow_count at ADDR, see below), when ADDR is given
 *   S <cycle> <dir>         a rising STEP edge: its cycle, and the DIR pin's level then
 *   D <cycle> <level>       a DIR change
 *   C <cycle> <bytes>       (lockstep) the AVR reached the granted cycle; <bytes>: all
 *                           it has written to the pty so far
 *   LAG <us>                (free-running) every second: the most the simulation fell behind real
 *                           time in that second (µs)
 *
 * Real time: the AVR runs as fast as the host lets it, and this loop sleeps
 * whenever the simulated time (cycle / 16 MHz) is ahead of the wall clock since
 * cycle 0, checked every 160 cycles (10 µs). So the simulation never runs ahead
 * of real time; when the host is too busy it falls behind, by LAG (simavr needs
 * about 0.6 s of one core per simulated second; a 2-core machine shared by a
 * dozen busy processes gives it a tenth of that). Free-running, the board then
 * lives in slow motion while the author's wall clock does not, which no real
 * board does: hence lockstep, where the author's clock is the board's.
 *
 * The wire: bytes from the pty go to the UART one per character time (10 bits
 * at the baud rate: 640 cycles at 250 000 baud), as a real UART delivers them,
 * and never into a full receive FIFO: simavr's UART model counts a parity bit
 * that 8N1 does not have (11 bits, 704 cycles a byte), so it takes bytes 10 %
 * slower than the wire brings them; its XOFF/XON say when to wait. The Arduino
 * core's own 64-byte receive ring behind it is the real one, and overflows as
 * on a chip if the sketch does not read it in time.
 * bytes the sketch transmits are written to the pty as simavr's UART emits them
 * (it paces them at the baud rate too). A slave fd stays open here, so when the
 * Node side closes the port (a link cut) the device keeps running and its
 * output is dropped once the pty's buffer is full, as a USB-serial chip with no
 * host would.
 *
 * micros(): Arduino's Timer 0 runs at clk/64 and counts its overflows in
 * timer0_overflow_count; micros() = (overflows·256 + TCNT0)·4. An overflow comes
 * every 256 counts of 64 cycles: 16 384 cycles, 1 024 µs. The first time the count
 * changes to n, at cycle c, the overflow happened at c − k, k being the
 * interrupt's latency up to the store (~40 cycles, ~3 µs), so micros() read 0 at
 * cycle c − k − 16 384·n. MICROS0 takes k = 40. (This said 1 024 cycles an
 * overflow until the HIL test compared the clock model with it: MICROS0 was then
 * 960 µs late.)
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <simavr/avr_ioport.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_irq.h>

#define F_CPU 16000000ULL
#define ISR_STORE_LATENCY 40
#define CYCLES_PER_OVERFLOW (64ULL * 256ULL) /* Timer 0 at clk/64, 8 bits */

static avr_t *avr;
static int master = -1, slave = -1;
static uint64_t t0_ns;
static int dirLevel = 0;

static uint64_t monotonic_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint64_t)ts.tv_sec * 1000000000ULL + (uint64_t)ts.tv_nsec;
}

/* ---------------------------------------------------------------- device -> pty */
static uint8_t txBuf[1 << 16];
static size_t txHead = 0, txLen = 0;
static unsigned long txDropped = 0;
static unsigned long long txWritten = 0; /* bytes written to the pty so far */
static void onUartOut(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if (txLen == sizeof txBuf) { txDropped++; return; }
  txBuf[(txHead + txLen++) % sizeof txBuf] = (uint8_t)value;
}
static void flushTx(void) {
  while (txLen > 0) {
    size_t chunk = sizeof txBuf - txHead;
    if (chunk > txLen) chunk = txLen;
    ssize_t n = write(master, txBuf + txHead, chunk);
    if (n <= 0) {
      /* nobody reads the pty (a link cut): the wire drops what it cannot carry */
      if (n < 0 && (errno == EAGAIN || errno == EIO)) { txDropped += txLen; txLen = 0; }
      return;
    }
    txHead = (txHead + (size_t)n) % sizeof txBuf;
    txLen -= (size_t)n;
    txWritten += (unsigned long long)n;
  }
}

/* ---------------------------------------------------------------- pty -> device */
static uint8_t rxBuf[4096];
static size_t rxHead = 0, rxLen = 0;
static uint64_t nextRxCycle = 0, cyclesPerByte = 640;
static avr_irq_t *uartIn;
static int xoff = 0;
static void onXoff(struct avr_irq_t *irq, uint32_t value, void *param) { (void)irq; (void)value; (void)param; xoff = 1; }
static void onXon(struct avr_irq_t *irq, uint32_t value, void *param) { (void)irq; (void)value; (void)param; xoff = 0; }
static void pollRx(void) {
  if (rxLen == 0) {
    ssize_t n = read(master, rxBuf, sizeof rxBuf);
    if (n > 0) { rxHead = 0; rxLen = (size_t)n; }
  }
  if (rxLen > 0 && !xoff && avr->cycle >= nextRxCycle) {
    avr_raise_irq(uartIn, rxBuf[rxHead++]);
    rxLen--;
    /* the next byte one character time after this one, or after now if the line was idle */
    nextRxCycle = (nextRxCycle + cyclesPerByte > avr->cycle ? nextRxCycle : avr->cycle) + cyclesPerByte;
  }
}

/* ---------------------------------------------------------------- pins */
static void onStep(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if (value) printf("S %llu %d\n", (unsigned long long)avr->cycle, dirLevel);
}
static void onDir(struct avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  int level = value ? 1 : 0;
  if (level != dirLevel) printf("D %llu %d\n", (unsigned long long)avr->cycle, level);
  dirLevel = level;
}

/* Reads stdin until a grant beyond `current` ("G <cycle>"); 0 on "Q" or end of input. */
static uint64_t waitForGrant(uint64_t current) {
  char line[64];
  while (fgets(line, sizeof line, stdin)) {
    if (line[0] == 'Q') return 0;
    if (line[0] == 'G') {
      uint64_t g = strtoull(line + 2, 0, 10);
      if (g > current) return g;
    }
  }
  return 0;
}

static int openPty(char *path, size_t size) {
  master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) < 0 || unlockpt(master) < 0 || ptsname_r(master, path, size) != 0) return -1;
  slave = open(path, O_RDWR | O_NOCTTY);
  if (slave < 0) return -1;
  struct termios tio;
  tcgetattr(slave, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave, TCSANOW, &tio);
  return fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s FILE.elf [--baud B] [--step-pin N] [--dir-pin N] [--overflow-count ADDR] [--seconds S]\n", argv[0]);
    return 2;
  }
  unsigned long baud = 250000, stepPin = 2, dirPin = 5, overflowAddr = 0;
  double seconds = 0;
  int lockstep = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--baud")) baud = strtoul(argv[i + 1], 0, 0);
    else if (!strcmp(argv[i], "--step-pin")) stepPin = strtoul(argv[i + 1], 0, 0);
    else if (!strcmp(argv[i], "--dir-pin")) dirPin = strtoul(argv[i + 1], 0, 0);
    else if (!strcmp(argv[i], "--overflow-count")) overflowAddr = strtoul(argv[i + 1], 0, 0);
    else if (!strcmp(argv[i], "--seconds")) seconds = atof(argv[i + 1]);
    else if (!strcmp(argv[i], "--lockstep")) lockstep = atoi(argv[i + 1]);
    else { fprintf(stderr, "unknown option %s\n", argv[i]); return 2; }
  }
  cyclesPerByte = (uint64_t)(10.0 * F_CPU / baud + 0.5);

  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(argv[1], &fw) != 0) { fprintf(stderr, "cannot read %s\n", argv[1]); return 1; }
  avr = avr_make_mcu_by_name("atmega328p");
  if (!avr) { fprintf(stderr, "simavr has no atmega328p\n"); return 1; }
  avr_init(avr);
  avr->frequency = F_CPU;
  avr->log = LOG_ERROR;
  avr_load_firmware(avr, &fw);

  /* UART0: no stdio echo from simavr, bytes through our irqs */
  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~AVR_UART_FLAG_STDIO;
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onUartOut, NULL);
  uartIn = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF), onXoff, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON), onXon, NULL);
  /* Uno pins D0-D7 are PORTD 0-7, D8-D13 PORTB 0-5 */
  char stepPort = stepPin < 8 ? 'D' : 'B', dirPort = dirPin < 8 ? 'D' : 'B';
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ(stepPort), stepPin % 8), onStep, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ(dirPort), dirPin % 8), onDir, NULL);

  char path[128];
  if (openPty(path, sizeof path) < 0) { perror("pty"); return 1; }
  printf("PTY %s\n", path);
  t0_ns = monotonic_ns();
  printf("T0 %llu\n", (unsigned long long)t0_ns);
  fflush(stdout);

  uint32_t lastOverflows = 0;
  int micros0Known = overflowAddr == 0;
  uint64_t nextCheck = 0, nextFlush_ns = t0_ns, nextLag_ns = t0_ns + 1000000000ULL;
  int64_t lagMax_ns = 0;
  const uint64_t stop_cycle = seconds > 0 ? (uint64_t)(seconds * F_CPU) : UINT64_MAX;
  uint64_t granted = lockstep ? 0 : UINT64_MAX;
  for (;;) {
    int state = avr_run(avr);
    if (state == cpu_Done || state == cpu_Crashed) { fprintf(stderr, "the AVR stopped (state %d)\n", state); break; }
    if (!micros0Known) {
      uint32_t n = (uint32_t)avr->data[overflowAddr] | (uint32_t)avr->data[overflowAddr + 1] << 8 |
                   (uint32_t)avr->data[overflowAddr + 2] << 16 | (uint32_t)avr->data[overflowAddr + 3] << 24;
      if (n != lastOverflows && lastOverflows == 0 && n > 0) {
        printf("MICROS0 %llu\n", (unsigned long long)(avr->cycle - ISR_STORE_LATENCY - CYCLES_PER_OVERFLOW * n));
        micros0Known = 1;
      }
      lastOverflows = n;
    }
    if (avr->cycle < nextCheck) continue;
    nextCheck = avr->cycle + 160;
    if (avr->cycle >= stop_cycle) break;
    pollRx();
    if (txLen && !lockstep) flushTx();
    if (avr->cycle >= granted) {
      printf("C %llu %llu\n", (unsigned long long)avr->cycle, txWritten);
      fflush(stdout);
      granted = waitForGrant(granted);
      if (granted == 0) break;
      /* What the sketch sent during the last quantum goes out now that the
       * author's clock has reached its end: it can only arrive late, as on a
       * real link, never before the author's clock says it was sent. */
      if (txLen) flushTx();
    }
    /* keep pace: simulated ns since cycle 0 against wall ns since T0 */
    uint64_t sim_ns = avr->cycle * 1000ULL / (F_CPU / 1000000ULL);
    uint64_t now = monotonic_ns();
    int64_t ahead = (int64_t)sim_ns - (int64_t)(now - t0_ns);
    if (ahead > 200000) {
      struct timespec ts = {0, (long)ahead};
      nanosleep(&ts, NULL);
      now = monotonic_ns();
    } else if (!lockstep && -ahead > lagMax_ns) {
      lagMax_ns = -ahead;
    }
    if (now >= nextFlush_ns) { fflush(stdout); nextFlush_ns = now + 5000000ULL; }
    if (!lockstep && now >= nextLag_ns) {
      printf("LAG %lld\n", (long long)(lagMax_ns / 1000));
      lagMax_ns = 0;
      nextLag_ns = now + 1000000000ULL;
    }
  }
  fprintf(stderr, "simavr_uno_pty: %llu cycles, %lu bytes to the pty dropped\n", (unsigned long long)avr->cycle, txDropped);
  fflush(stdout);
  return 0;
}
