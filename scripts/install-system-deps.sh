#!/usr/bin/env bash
# Installs every Debian package the MAXL build and tests need. Idempotent:
# packages already present are skipped, so running it again is cheap.
#
#   chromium                 Playwright e2e tests and the ui bench (Debian's build;
#                            Playwright cannot download its own browser here)
#   gcc-avr avr-libc         AVR builds of the firmware examples (avr-gcc 5.4)
#   arduino-core-avr         the real Arduino AVR core
#   arduino-mk               Arduino.mk, the makefile that builds sketches
#   simavr libsimavr-dev     runs AVR ELFs for the firmware benchmark, and the Uno behind a
#                            pty for the hardware-in-the-loop suite (scripts/firmware-hil.sh)
#   cmake libgtest-dev nlohmann-json3-dev
#                            host build of the firmware library, its GoogleTest suite,
#                            and JSON for reading the shared test vectors
#   clang lld wasi-libc libc++-14-dev-wasm32 libc++abi-14-dev-wasm32
#   libclang-rt-14-dev-wasm32
#                            wasm32 builds of the firmware for the simulator
#   libclang-rt-14-dev       libFuzzer and the sanitizers for the fuzz target
#   valgrind                 callgrind instruction counts in the firmware bench
#   socat                    pseudo-terminal pairs for the Node serialport link's tests
set -euo pipefail

PACKAGES=(
  chromium
  gcc-avr avr-libc arduino-core-avr arduino-mk simavr libsimavr-dev
  cmake make g++ libgtest-dev nlohmann-json3-dev pkg-config
  clang lld wasi-libc libc++-14-dev-wasm32 libc++abi-14-dev-wasm32 libclang-rt-14-dev-wasm32
  libclang-rt-14-dev
  valgrind
  socat
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "system packages: all ${#PACKAGES[@]} present"
  exit 0
fi

echo "system packages: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
  else
    echo "Not root and no sudo. Run as root:" >&2
    echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
