// Self-test of the AVR assembly in maxl/readers/step_count.h: countJump()
// must equal the portable form countJumpPortable() (tested on the host
// against a walk over the thresholds: firmware/test/step_count_test.cpp) in
// its count and in the next threshold, for edge values and 30 000
// pseudo-random cases across the domain (step sizes from 2^-16 to 2^23 units,
// positions up to ~140 steps either side, on a threshold's ceiling or a unit
// short of it); divideWindow() must equal C's 32-bit division for edge
// values and 100 000 pseudo-random dividends and divisors of every length;
// and whole windows (MAXL_StepGenerator::planWindow, the assembly's path)
// must equal their twin's K whole steps away, 2^30 units out, where the count
// goes by the C walk (as the host's StepCount.WindowsMatchTheWalkingTwin).
// timesR() (maxl/readers/step_times.h, AVR assembly) must equal
// timesRPortable() for edge values and 40 000 pseudo-random cases (R below
// 2^31 as planWindow makes it, every length of R, whole and frac).
// MAXL_StepGenerator::stepToward (assembly that first asks whether a step is
// due, maxl_stepToward) must give the count and leave the generator as the C
// count alone does (maxl_stepTowardDue, which finds none due by itself), for
// 30 000 pseudo-random generators and positions a few units either side of a
// threshold's ceiling, both ways, near the origin and 2^30 units out.
// Run in simavr by scripts/firmware-avr.sh; prints "COUNT OK <n>" or the
// first mismatch.
#include <MAXL.h>
#include <avr/sleep.h>

#include "maxl/readers/step_count.h"
#include "maxl/readers/step_times.h"

using namespace maxl_fw;

uint32_t rngState = 2463534242UL;
uint32_t next() {  // xorshift32
  rngState ^= rngState << 13;
  rngState ^= rngState >> 17;
  rngState ^= rngState << 5;
  return rngState;
}

bool same(int32_t m, uint32_t sWhole, uint16_t sFrac, int32_t upWhole, uint16_t upFrac, bool up) {
  if (!countJumpFits(m, upWhole, (int32_t)sWhole) || (!sWhole && !sFrac)) return true;  // outside the domain
  uint32_t aw = (uint32_t)upWhole, pw = (uint32_t)upWhole;
  uint16_t af = upFrac, pf = upFrac;
  uint8_t a = countJump(m, sWhole, sFrac, aw, af, up);
  uint8_t p = countJumpPortable(m, sWhole, sFrac, pw, pf, up);
  if (a == p && (a == 0 || a == COUNT_NOT_HERE || (aw == pw && af == pf))) return true;
  Serial.print("COUNT MISMATCH m=");
  Serial.print(m);
  Serial.print(" S=");
  Serial.print(sWhole);
  Serial.print(" F=");
  Serial.print(sFrac);
  Serial.print(" U=");
  Serial.print(upWhole);
  Serial.print(":");
  Serial.print(upFrac);
  Serial.print(up ? " up" : " down");
  Serial.print(" asm=");
  Serial.print(a);
  Serial.print(" portable=");
  Serial.println(p);
  return false;
}

bool sameQuotient(uint32_t n, uint32_t d) {
  if (!d) return true;
  uint32_t a = divideWindow(n, d), p = n / d;
  if (a == p) return true;
  Serial.print("COUNT DIVIDE MISMATCH n=");
  Serial.print(n);
  Serial.print(" d=");
  Serial.print(d);
  Serial.print(" asm=");
  Serial.print(a);
  Serial.print(" C=");
  Serial.println(p);
  return false;
}

bool sameTimes(uint32_t whole, uint16_t frac, uint32_t r) {
  r &= 0x7FFFFFFFUL;  // planWindow's clamp
  uint32_t a = timesR(whole, frac, r), p = timesRPortable(whole, frac, r);
  if (a == p) return true;
  Serial.print("COUNT TIMES MISMATCH whole=");
  Serial.print(whole);
  Serial.print(" frac=");
  Serial.print(frac);
  Serial.print(" r=");
  Serial.print(r);
  Serial.print(" asm=");
  Serial.print(a);
  Serial.print(" C=");
  Serial.println(p);
  return false;
}

// stepToward's assembly against the C count on twin generators.
bool dueMatches(uint32_t& n) {
  for (uint16_t trial = 0; trial < 300; trial++) {
    uint8_t k = (uint8_t)(next() % 14);
    float stepsPerUnit = 65536.0f / (float)(((uint32_t)1 << k) + (next() % 7 == 0 ? next() % 1000 : 0));
    MAXL_StepGenerator g(2, 5, stepsPerUnit);
    int32_t p = (int32_t)(next() % 0x20000000UL) - 0x10000000L;
    if (trial & 1) p += 0x40000000L;  // beyond countJump's domain: the walk
    g.reference(p);
    for (uint8_t i = 0; i < 100; i++, n++) {
      int32_t span = (int32_t)1 << (next() % 16);
      int32_t units = p + (int32_t)(next() % (uint32_t)(2 * span + 1)) - span;
      uint8_t max = (uint8_t)(next() % 4 == 0 ? next() % 8 : 127);
      int8_t direction = (next() & 1) ? 1 : -1;
      MAXL_StepGenerator a = g, c = g;
      uint8_t ka = maxl_stepToward(&a, units, max, direction);
      uint8_t kc = maxl_stepTowardDue(&c, units, max, direction);
      if (ka != kc || memcmp(&a, &c, sizeof a) != 0) {
        Serial.print("COUNT DUE MISMATCH trial=");
        Serial.print(trial);
        Serial.print(" units=");
        Serial.print(units);
        Serial.print(" direction=");
        Serial.print(direction);
        Serial.print(" asm=");
        Serial.print(ka);
        Serial.print(" C=");
        Serial.println(kc);
        return false;
      }
      g = a;
      p = units;
    }
  }
  return true;
}

// Windows of the assembly's path against the walk's, on twin generators (see
// the top); returns false at the first difference.
bool windowsMatchTheWalk(uint32_t& n) {
  for (uint8_t trial = 0; trial < 120; trial++) {
    uint8_t k = (uint8_t)(next() % 13);  // s = 2^k units
    int32_t s = (int32_t)1 << k;
    int32_t K = (int32_t)((1L << 30) / s + 1);
    int32_t shift = K * s;
    MAXL_StepGenerator fast(2, 5, 65536.0f / (float)s), walking(2, 5, 65536.0f / (float)s);
    int32_t p = (int32_t)(next() % 0x20000000UL) - 0x10000000L;
    fast.reference(p);
    walking.reference(p + shift);
    for (uint8_t i = 0; i < 50; i++, n++) {
      uint8_t kind = (uint8_t)(next() % 16);
      uint16_t w = kind == 0 ? (uint16_t)(1 + next() % 4000) : (uint16_t)(128u << (next() % 5));
      int32_t maxSteps = kind == 1 ? 0 : kind == 2 ? 200 : kind == 3 ? 3 : 110;
      int32_t delta = maxSteps ? ((int32_t)(next() % (uint32_t)(2 * maxSteps + 1)) - maxSteps) * s + (int32_t)(next() % (uint32_t)s) : 0;
      int32_t lag = kind == 4 ? (int32_t)(next() % 4000) : (int32_t)(next() % 40);
      MAXL_StepWindow a, b;
      fast.planWindow(w, p, p + delta, lag, a);
      walking.planWindow(w, p + shift, p + delta + shift, lag, b);
      bool same = a.runs == b.runs && walking.steps() - fast.steps() == K;
      for (uint8_t r = 0; same && r < a.runs; r++)
        same = a.run[r].first == b.run[r].first && a.run[r].interval == b.run[r].interval &&
               a.run[r].count == b.run[r].count && a.run[r].backward == b.run[r].backward;
      if (!same) {
        Serial.print("COUNT WINDOW MISMATCH trial=");
        Serial.print(trial);
        Serial.print(" window=");
        Serial.println(i);
        return false;
      }
      p += delta;
      if (p > 0x18000000L || p < -0x18000000L) break;
    }
  }
  return true;
}

void setup() {
  Serial.begin(1000000);
  uint32_t n = 0;
  bool ok = true;
  // edges: the domain's corners, steps of 2^-16 and just under 2^23 units
  const int32_t ws[] = {0, 1, -1, 0x1FFFFF00L, -0x1FFFFF00L, 0x1FFFFFFFL, -0x20000000L};
  const uint32_t Ss[] = {0, 1, 819, 0x7FFFFFUL};
  const uint16_t Fs[] = {0, 1, 0x8000, 0xFFFF};
  for (uint8_t i = 0; i < 7 && ok; i++)
    for (uint8_t j = 0; j < 7 && ok; j++)
      for (uint8_t a = 0; a < 4 && ok; a++)
        for (uint8_t b = 0; b < 4 && ok; b++)
          for (uint8_t up = 0; up < 2 && ok; up++, n++) ok = same(ws[i], Ss[a], Fs[b], ws[j], (uint16_t)next(), up);
  for (uint32_t i = 0; i < 30000UL && ok; i++) {
    uint8_t bits = (uint8_t)(next() % 39);  // s below 2^(bits + 1) in Q16, S below 2^23
    uint64_t sq = (((uint64_t)next() << 32) | next()) & ((2ULL << bits) - 1);
    if (!sq) sq = 1;
    uint32_t S = (uint32_t)(sq >> 16);
    uint16_t F = (uint16_t)sq;
    int32_t upWhole = (int32_t)(next() % 0x3C000000UL) - 0x1E000000L;
    uint16_t upFrac = (uint16_t)next();
    bool up = next() & 1;
    int64_t U = (int64_t)upWhole * 65536 + upFrac;
    uint8_t steps = (uint8_t)(next() % 140);
    int64_t target = up ? U + (int64_t)steps * (int64_t)sq : U - (int64_t)steps * (int64_t)sq;
    int32_t m = (int32_t)(target >> 16);  // floor
    switch (next() % 4) {
      case 0: m += 1; break;                      // past the threshold's floor: its ceiling or more
      case 1: m -= 1; break;
      case 2: m += (int32_t)(next() % 65536) - 32768; break;
      default: break;
    }
    ok = same(m, S, F, upWhole, upFrac, up);
    n++;
  }
  const uint32_t es[] = {0, 1, 2, 255, 256, 65535UL, 65536UL, 0xFFFFFFUL, 0x1000000UL, 0x7FFFFFFFUL, 0x80000000UL,
                         0x80000001UL, 0xFFFFFFFEUL, 0xFFFFFFFFUL};
  for (uint8_t i = 0; i < 14 && ok; i++)
    for (uint8_t j = 0; j < 14 && ok; j++, n++) ok = sameQuotient(es[i], es[j]);
  for (uint32_t i = 0; i < 100000UL && ok; i++, n++) {
    uint32_t d = next() >> (next() % 32);
    uint32_t w = 128UL << (next() % 5);
    uint32_t dividend = (i & 1) ? (w << 20) + d - 1 : next() >> (next() % 32);
    ok = sameQuotient(dividend, d);
  }
  const uint32_t ts[] = {0, 1, 15, 16, 255, 0xFFFFUL, 0x10000UL, 0xFFFFFFUL, 0x7FFFFFFFUL, 0x80000000UL, 0xFFFFFFFFUL};
  const uint16_t tf[] = {0, 1, 0x8000, 0xFFFF};
  for (uint8_t i = 0; i < 11 && ok; i++)
    for (uint8_t j = 0; j < 11 && ok; j++)
      for (uint8_t f = 0; f < 4 && ok; f++, n++) ok = sameTimes(ts[i], tf[f], ts[j]);
  for (uint32_t i = 0; i < 40000UL && ok; i++, n++)
    ok = sameTimes(next() >> (next() % 32), (uint16_t)(next() >> (next() % 16)), next() >> (next() % 32));
  if (ok) ok = dueMatches(n);
  if (ok) ok = windowsMatchTheWalk(n);
  if (ok) {
    Serial.print("COUNT OK ");
    Serial.println(n);
  }
  Serial.flush();
  cli();
  sleep_enable();
  sleep_cpu();
}

void loop() {}
