#!/usr/bin/env bash
# Builds every firmware example for the Arduino Uno (ATmega328P) with Debian's
# arduino-core-avr, gcc-avr and arduino-mk, and prints flash and RAM for each.
# Fails if an example leaves less than 25 % of the Uno's 2048 bytes of RAM
# free, or less than 10 % of its flash (the room a fix or a feature needs;
# examples make room with compile-time options, firmware/README.md). RAM here is static RAM (.data + .bss, from avr-size); the stack grows
# down from the top of RAM into what is left, so the free 25 % is the stack's.
#
#   bash scripts/firmware-avr.sh [Example ...]     (default: all examples)
# Output: firmware/build/avr/<Example>/<Example>.elf|.hex
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/firmware/build/avr"
RAM_TOTAL=2048
FLASH_TOTAL=32256  # 32 KiB minus the Uno's 512-byte optiboot
MIN_FREE_PERCENT=25
MIN_FLASH_FREE_PERCENT=10

if [ "$#" -gt 0 ]; then examples=("$@"); else
  examples=()
  for d in "$root"/firmware/examples/*/; do examples+=("$(basename "$d")"); done
fi

status=0
printf '%-16s %8s %7s %9s %7s\n' example flash flash% staticRAM free%
for name in "${examples[@]}"; do
  dir="$root/firmware/examples/$name"
  if ! bash "$root/scripts/firmware-avr-sketch.sh" "$dir" "$out"; then
    status=1
    continue
  fi
  # Berkeley format: text data bss dec hex filename
  read -r text data bss _ < <(avr-size "$out/$name/$name.elf" | tail -n 1)
  flash=$((text + data))
  ram=$((data + bss))
  free=$((RAM_TOTAL - ram))
  freePercent=$((100 * free / RAM_TOTAL))
  printf '%-16s %8d %6d%% %9d %6d%%\n' "$name" "$flash" $((100 * flash / FLASH_TOTAL)) "$ram" "$freePercent"
  if [ $((100 * free)) -lt $((MIN_FREE_PERCENT * RAM_TOTAL)) ]; then
    echo "FAIL $name: $ram bytes of static RAM leave $free bytes ($freePercent %) free; at least $MIN_FREE_PERCENT % must stay free for the stack"
    status=1
  fi
  if [ "$flash" -gt "$FLASH_TOTAL" ]; then
    echo "FAIL $name: $flash bytes of flash do not fit in $FLASH_TOTAL"
    status=1
  elif [ $((100 * (FLASH_TOTAL - flash))) -lt $((MIN_FLASH_FREE_PERCENT * FLASH_TOTAL)) ]; then
    echo "FAIL $name: $flash bytes of flash leave $((FLASH_TOTAL - flash)) bytes free, under $MIN_FLASH_FREE_PERCENT %; leave out what it does not use (firmware/README.md, compile-time options)"
    status=1
  fi
done
echo "(static RAM = .data + .bss of $RAM_TOTAL bytes; the stack grows down from the top of RAM into the free part)"

# AVR assembly cannot run in the host tests: each self-test sketch checks it
# against its portable form in simavr and prints "<WORD> OK <cases>".
#   avr_self_test SKETCH WORD LABEL
avr_self_test() {
  local sketch="$1" word="$2" label="$3" result
  if bash "$root/scripts/firmware-avr-sketch.sh" "$root/firmware/bench/$sketch" "$out"; then
    result="$(timeout 300 simavr -m atmega328p -f 16000000 "$out/$sketch/$sketch.elf" 2>&1 | tr -d '\r' | sed 's/\x1b\[[0-9;]*m//g' | grep -E "^$word" || true)"
    echo "AVR $label self-test in simavr: ${result:-no output}"
    case "$result" in "$word OK"*) ;; *) status=1 ;; esac
  else
    status=1
  fi
}
# The evaluation hot path (motion/fixed_point.h).
avr_self_test MulHiCheck MULHI mulhi16
# The window count (readers/step_count.h; its portable form is checked on the
# host against a threshold walk).
avr_self_test StepCountCheck COUNT "step count"
# The step vector (readers/step_timer.cpp) against its C form, StepTimer::interrupt().
avr_self_test StepVectorCheck VECTOR "step vector"
# The step vector's fast path (readers/step_timer.cpp) is AVR assembly, which
# the host tests cannot run either: drive benchmark sketches in simavr with
# real frames (bench/firmware/simavr_steps.c, the step-rate benchmark's
# harness) and require every step of every stepper, none early and none later
# than one step period. This checks correctness, not speed: the benchmark
# (npm run bench -- firmware) finds the highest rates.
#   one stepper (the Stepper example's device), 10 kHz;
#   two (BlotPlotter's CoreXY pair): the Blot preset's 120 mm/s along x (both
#   motors at 9 600 Hz) and along a line at 30° (motor a at 13 115 Hz, b at 3 515);
#   three (the CncShield example's x, y, z), 4 kHz each (50 mm/s at 80 steps/mm).
timed_check() {  # label sketch rate [VAR=value ...]
  local label="$1" sketch="$2" rate="$3"
  shift 3
  local result steps got expected missed nacks
  result="$(env "$@" timeout 300 "$out/simavr_steps" "$out/$sketch/$sketch.elf" "$rate" 2>/dev/null | tail -n 1)"
  steps="$(sed -n 's/.*"steps":\([0-9]*\),"expected":\([0-9]*\),"missed":\([0-9]*\),.*"nacks":\([0-9]*\).*/\1 \2 \3 \4/p' <<<"$result")"
  read -r got expected missed nacks <<<"${steps:-x x x x}"
  echo "AVR timed steps in simavr ($label): $got of $expected steps, $missed missed, $nacks nacks"
  if [ "$got" != "$expected" ] || [ "$missed" != 0 ] || [ "$nacks" != 0 ] || [ "$got" = 0 ]; then
    echo "FAIL AVR timed stepping ($label): $result"
    status=1
  fi
}
if bash "$root/scripts/firmware-avr-sketch.sh" "$root/firmware/bench/StepRate" "$out" &&
  bash "$root/scripts/firmware-avr-sketch.sh" "$root/firmware/bench/StepRateTwo" "$out" &&
  bash "$root/scripts/firmware-avr-sketch.sh" "$root/firmware/bench/StepRateThree" "$out" &&
  gcc -O2 -Wall -o "$out/simavr_steps" "$root/bench/firmware/simavr_steps.c" -lsimavr -lm; then
  timed_check "one stepper, 10 kHz" StepRate 10000
  timed_check "two steppers, 120 mm/s along x" StepRateTwo 9600 STEPPERS=2
  timed_check "two steppers, 120 mm/s at 30°" StepRateTwo 13115 STEPPERS=2 ANGLE_DEG=30
  timed_check "three steppers, 4 kHz each" StepRateThree 4000 STEPPERS=3 CRUISE_SEGMENTS=4
else
  status=1
fi
exit $status
