// Host build of the evaluation benchmark, for callgrind: N evaluations of a
// running one-slot segment (the same move as firmware/bench/EvalCycles), so
// that instructions per evaluation = (Ir(N2) - Ir(N1)) / (N2 - N1).
//   eval_host N
#include <stdio.h>
#include <stdlib.h>

#include "maxl/motion/motion.h"
#include "../../firmware/bench/bench_trapezoid.h"

using namespace maxl_fw;

int main(int argc, char** argv) {
  long n = argc > 1 ? atol(argv[1]) : 1000;
  static Motion motion;
  int32_t p0[1] = {0};
  int32_t delta[1] = {100L * 65536};
  long done = 0;
  int64_t checksum = 0;
  while (done < n) {
    motion.reset();
    motion.setActiveSlots(1);
    motion.setBase(p0, 1);
    benchQueueTrapezoid(motion, 100.0f, 200.0f, 3000.0f, delta, 1, 1000);
    for (uint32_t t = 1000; done < n && (motion.mode() != Motion::IDLE || t == 1000); t += 20, done++) {
      motion.tick(t);
      checksum += motion.position(0);
    }
  }
  printf("%ld %lld\n", done, (long long)checksum);
  return 0;
}
