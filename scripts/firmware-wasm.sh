#!/usr/bin/env bash
# Builds every firmware example to wasm32 for the simulator, with Debian's
# clang 14, wasi-libc and libc++-14-dev-wasm32, against the Arduino shim in
# firmware/wasm/shim. Output: public/firmware/<Example>.wasm (committed: the
# workbench serves them), then checks that each module instantiates and
# answers a HELLO_REQUEST in Node (scripts/firmware-wasm-smoke.mjs).
#
# The build is deterministic: fixed input order, relative paths, no debug
# information, so the same sources give the same bytes. `--check` rebuilds
# into firmware/build/wasm and fails if any committed .wasm differs.
#
#   bash scripts/firmware-wasm.sh [--check] [Example ...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
if [ "$#" -gt 0 ]; then examples=("$@"); else
  examples=()
  for d in firmware/examples/*/; do examples+=("$(basename "$d")"); done
fi

out="public/firmware"
[ "$check" = 1 ] && out="firmware/build/wasm"
mkdir -p "$out"

# Sorted, relative source lists: the link order, and so the bytes, never vary.
mapfile -t library < <(find firmware/src -name '*.cpp' | LC_ALL=C sort)
mapfile -t shim < <(find firmware/wasm/shim -name '*.cpp' | LC_ALL=C sort)

flags=(
  --target=wasm32-wasi -O2 -std=c++11
  -fno-exceptions -fno-rtti -g0 -ffp-contract=off
  -Wall -Wextra -Werror -Wno-unused-parameter
  -nostartfiles -Wl,--no-entry -Wl,--export=__wasm_call_ctors -Wl,--strip-all
  -Ifirmware/wasm/shim -Ifirmware/src
)

status=0
for name in "${examples[@]}"; do
  sketch="firmware/examples/$name/$name.ino"
  target="$out/$name.wasm"
  # The example's compile-time options (-D..., firmware/README.md), as on the
  # board; its AVR code-size options (-m...) are the AVR build's only.
  options=()
  if [ -f "firmware/examples/$name/build_flags.txt" ]; then
    for o in $(cat "firmware/examples/$name/build_flags.txt"); do case "$o" in -D*) options+=("$o") ;; esac; done
  fi
  # An .ino is C++ with Arduino.h included first, as the Arduino tools build it.
  if ! clang++ "${flags[@]}" "${options[@]}" -Ifirmware/examples/"$name" \
      -x c++ -include Arduino.h "$sketch" -x none "${library[@]}" "${shim[@]}" -o "$target"; then
    echo "FAIL $name: wasm build error"
    status=1
    continue
  fi
  size=$(stat -c %s "$target")
  if [ "$check" = 1 ]; then
    if cmp -s "$target" "public/firmware/$name.wasm"; then
      echo "$name.wasm: $size bytes, identical to the committed public/firmware/$name.wasm"
    else
      echo "FAIL $name.wasm: a rebuild differs from the committed public/firmware/$name.wasm (rebuild with bash scripts/firmware-wasm.sh and commit)"
      status=1
    fi
  else
    echo "$name.wasm: $size bytes -> $target"
  fi
done
[ "$status" = 0 ] || exit $status

node scripts/firmware-wasm-smoke.mjs "$out" "${examples[@]}"
