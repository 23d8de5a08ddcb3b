#!/usr/bin/env bash
# Builds one sketch that uses the MAXL library for the Arduino Uno with
# Debian's arduino-core-avr and arduino-mk. Used by firmware-avr.sh (examples,
# the AVR self-test) and bench/firmware.mjs (benchmark sketches).
#
#   bash scripts/firmware-avr-sketch.sh SKETCH_DIR OUT_DIR
# Output: OUT_DIR/<Name>/<Name>.elf (Name = the sketch directory's name);
# the build log is OUT_DIR/<Name>.log. Prints nothing on success.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
dir="$(cd "$1" && pwd)"
mkdir -p "$2"
out="$(cd "$2" && pwd)"
name="$(basename "$dir")"

mkdir -p "$out/libraries"
# arduino-mk finds user libraries by directory name: MAXL -> firmware/
ln -sfn "$root/firmware" "$out/libraries/MAXL"
libs="MAXL"
if grep -q '<Wire.h>' "$dir"/*.ino "$dir"/*.h 2>/dev/null; then libs="MAXL Wire"; fi
# A sketch's own build options, one line in its build_flags.txt: the
# library's compile-time options (-DMAXL_...=0, firmware/README.md), which
# apply to the library's sources too, and AVR code-size options (-mcall-prologues,
# -mrelax). With LTO the code is generated at link time, so they go to the
# link too.
options=""
if [ -f "$dir/build_flags.txt" ]; then options="$(tr '\n' ' ' < "$dir/build_flags.txt")"; fi
# make rebuilds on changed sources, not on changed flags: start clean when they changed.
stamp="$out/$name.flags"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$options" ]; then rm -rf "${out:?}/$name"; fi
mkdir -p "$out/$name"
printf '%s' "$options" > "$stamp"
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
CPPFLAGS += -DDECIMAL_DIG=9 $options
LDFLAGS += $options
include /usr/share/arduino/Arduino.mk
MK
log="$out/$name.log"
if ! make -C "$dir" -f "$mk" "$out/$name/$name.elf" > "$log" 2>&1; then
  echo "FAIL $name: build error; last lines of $log:"
  tail -n 30 "$log"
  exit 1
fi
