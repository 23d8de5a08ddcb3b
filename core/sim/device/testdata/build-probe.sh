#!/bin/sh
# Rebuilds probe.wasm from probe.c (checked in, so tests need no compiler).
set -e
cd "$(dirname "$0")"
clang --target=wasm32 -O2 -nostdlib -Wl,--no-entry -o probe.wasm probe.c
