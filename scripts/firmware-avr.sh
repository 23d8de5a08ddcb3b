#!/usr/bin/env bash
# Builds every firmware example for the Arduino Uno (ATmega328P) with Debian's
# arduino-core-avr, gcc-avr and arduino-mk, and prints flash and RAM for each.
# Fails if an example leaves less than 25 % of the Uno's 2048 bytes of RAM
# free. RAM here is static RAM (.data + .bss, from avr-size); the stack grows
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

mkdir -p "$out/libraries"
# arduino-mk finds user libraries by directory name: MAXL -> firmware/
ln -sfn "$root/firmware" "$out/libraries/MAXL"

if [ "$#" -gt 0 ]; then examples=("$@"); else
  examples=()
  for d in "$root"/firmware/examples/*/; do examples+=("$(basename "$d")"); done
fi

status=0
printf '%-16s %8s %7s %9s %7s\n' example flash flash% staticRAM free%
for name in "${examples[@]}"; do
  dir="$root/firmware/examples/$name"
  libs="MAXL"
  if grep -q '<Wire.h>' "$dir"/*.ino "$dir"/*.h 2>/dev/null; then libs="MAXL Wire"; fi
  mk="$out/$name.mk"
  cat > "$mk" <<MK
ARDUINO_DIR = /usr/share/arduino
ARDUINO_SKETCHBOOK = $out
USER_LIB_PATH = $out/libraries
BOARD_TAG = uno
ARDUINO_LIBS = $libs
OBJDIR = $out/$name
TARGET = $name
# Debian's gcc-avr 5.4 lacks DECIMAL_DIG, which the core's WString.cpp uses.
CPPFLAGS += -DDECIMAL_DIG=9
include /usr/share/arduino/Arduino.mk
MK
  log="$out/$name.log"
  if ! make -C "$dir" -f "$mk" "$out/$name/$name.elf" > "$log" 2>&1; then
    echo "FAIL $name: build error; last lines of $log:"
    tail -n 30 "$log"
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
  fi
done
echo "(static RAM = .data + .bss of $RAM_TOTAL bytes; the stack grows down from the top of RAM into the free part)"
exit $status
