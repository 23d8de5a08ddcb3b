#!/usr/bin/env bash
# Hardware in the loop: builds the Stepper example for the Arduino Uno (the real
# Arduino AVR core, as scripts/firmware-avr.sh does) and the libsimavr harness
# firmware/hil/simavr_uno_pty.c that runs it with its UART on a pseudo-terminal,
# then runs the vitest suite core/**/*.hil.ts (vitest.hil.config.ts), in which
# the Node core drives the board through `serialport` over that pty.
#
#   bash scripts/firmware-hil.sh            build, then test
#   bash scripts/firmware-hil.sh --build    build only
# Output: firmware/build/hil/{Stepper/Stepper.elf,simavr_uno_pty,board.json}
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/firmware/build/hil"
mkdir -p "$out"

fail() {
  echo "HIL FAIL: $*" >&2
  echo "HIL needs simavr and libsimavr-dev, gcc-avr, avr-libc, arduino-core-avr, arduino-mk (bash scripts/install-system-deps.sh)" >&2
  exit 1
}
[ -f /usr/include/simavr/sim_avr.h ] || fail "libsimavr-dev is not installed (no /usr/include/simavr/sim_avr.h)"
command -v avr-gcc >/dev/null || fail "avr-gcc is not installed"

bash "$root/scripts/firmware-avr-sketch.sh" "$root/firmware/examples/Stepper" "$out" || fail "the Uno build of the Stepper example failed (see $out/Stepper.log)"
gcc -O2 -Wall -Werror -o "$out/simavr_uno_pty" "$root/firmware/hil/simavr_uno_pty.c" -lsimavr -lm || fail "the simavr harness did not build"

# Arduino's micros() counts Timer 0 overflows in this variable (its RAM address
# minus the 0x800000 data-space offset of avr-nm's listing).
addr="$(avr-nm "$out/Stepper/Stepper.elf" | awk '$3 == "timer0_overflow_count" { print $1 }')"
[ -n "$addr" ] || fail "no timer0_overflow_count in Stepper.elf"
printf '{"elf":"%s","harness":"%s","overflowCount":%d}\n' \
  "$out/Stepper/Stepper.elf" "$out/simavr_uno_pty" $((16#$addr - 0x800000)) > "$out/board.json"

if [ "${1:-}" = "--build" ]; then exit 0; fi
cd "$root"
exec npx vitest run --config vitest.hil.config.ts
