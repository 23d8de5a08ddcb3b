// A minimal WS2812 ("NeoPixel") driver: no library needed.
//
// On the Uno (16 MHz) each bit is 20 cycles (1.25 µs): the line goes high,
// falls after 5 cycles (0.31 µs) for a 0 or 11 cycles (0.69 µs) for a 1, and
// stays low for the rest, as the WS2812B datasheet asks (T0H 0.4 µs, T1H
// 0.8 µs, ±0.15 µs); the counts assume a 16 MHz clock. Interrupts are off for
// one LED (24 bits, 30 µs) at a time and back on between LEDs, so the UART
// keeps its bytes; the short gap is far below the 50 µs that latches the strip.
//
// In the simulator the whole strip goes to the maxl_led_show import.
#ifndef WS2812_H
#define WS2812_H

#include <Arduino.h>

#if defined(__wasm__)
#include "maxl/hal/wasm_imports.h"
#endif
#if defined(__AVR__) && F_CPU != 16000000UL
#error "ws2812.h counts cycles for a 16 MHz AVR"
#endif

template <uint8_t PIN, uint8_t COUNT>
class Ws2812Strip {
 public:
  void begin() {
    pinMode(PIN, OUTPUT);
    digitalWrite(PIN, LOW);
  }
  void set(uint8_t i, uint8_t r, uint8_t g, uint8_t b) {
    if (i >= COUNT) return;
    rgb_[3 * i] = r;
    rgb_[3 * i + 1] = g;
    rgb_[3 * i + 2] = b;
  }
  void show() {
#if defined(__AVR__)
    volatile uint8_t* port = portOutputRegister(digitalPinToPort(PIN));
    uint8_t mask = digitalPinToBitMask(PIN);
    uint8_t hi = *port | mask;
    uint8_t lo = *port & (uint8_t)~mask;
    for (uint8_t i = 0; i < COUNT; i++) {
      uint8_t sreg = SREG;
      cli();
      // The strip wants G, R, B.
      sendByte(port, hi, lo, rgb_[3 * i + 1]);
      sendByte(port, hi, lo, rgb_[3 * i]);
      sendByte(port, hi, lo, rgb_[3 * i + 2]);
      SREG = sreg;
    }
#elif defined(__wasm__)
    maxl_led_show(PIN, rgb_, COUNT);
#endif
  }

 private:
#if defined(__AVR__)
  // 8 bits, MSB first, 20 cycles each. Both branches of the bit test take
  // two cycles (sbrc + mov, or a skipping sbrc), so every bit has the same
  // period. Cycle counts from the rising store:
  static inline void sendByte(volatile uint8_t* port, uint8_t hi, uint8_t lo, uint8_t byte) {
    uint8_t bits = 8;
    uint8_t next;
    __asm__ volatile(
        "1:                      \n\t"
        "st   %a[port], %[hi]    \n\t"  //  0-1  rise
        "mov  %[next], %[lo]     \n\t"  //  2
        "sbrc %[byte], 7         \n\t"  //  3    (3-4 when it skips)
        "mov  %[next], %[hi]     \n\t"  //  4    next = hi for a 1
        "st   %a[port], %[next]  \n\t"  //  5-6  a 0 falls: high 5 cycles, 0.31 µs
        "lsl  %[byte]            \n\t"  //  7
        "nop                     \n\t"  //  8
        "nop                     \n\t"  //  9
        "nop                     \n\t"  // 10
        "st   %a[port], %[lo]    \n\t"  // 11-12 a 1 falls: high 11 cycles, 0.69 µs
        "nop                     \n\t"  // 13
        "nop                     \n\t"  // 14
        "nop                     \n\t"  // 15
        "nop                     \n\t"  // 16
        "dec  %[bits]            \n\t"  // 17
        "brne 1b                 \n\t"  // 18-19 next bit rises at 20 (1.25 µs)
        : [byte] "+r"(byte), [bits] "+r"(bits), [next] "=&r"(next)
        : [port] "e"(port), [hi] "r"(hi), [lo] "r"(lo)
        : "memory");
  }
#endif
  uint8_t rgb_[3 * COUNT];
};

#endif
