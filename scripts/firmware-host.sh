#!/usr/bin/env bash
# Host build of the firmware library and its GoogleTest suite (CMake, Debian's
# libgtest-dev and nlohmann-json3-dev, no network), run through ctest.
#   bash scripts/firmware-host.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/firmware/build/host"
mkdir -p "$build"
cmake -S "$root/firmware/test" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
