#!/usr/bin/env bash
# Builds the libFuzzer target firmware/fuzz/fuzz_device.cpp (the whole device
# on the host hardware layer) with clang's fuzzer, ASan and UBSan, and runs it
# for a short, fixed time from the seed corpus in firmware/fuzz/corpus. New
# inputs go to firmware/build/fuzz/corpus (not the repo); a crash leaves its
# input in firmware/build/fuzz/ and fails.
#
#   bash scripts/firmware-fuzz.sh [seconds]        (default 25)
#   bash scripts/firmware-fuzz.sh --build          (only build firmware/build/fuzz/fuzz_device;
#                                                   `npm run bench -- fuzz` runs it at scale)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
seconds="${1:-25}"
out="firmware/build/fuzz"
mkdir -p "$out/corpus"

mapfile -t library < <(find firmware/src -name '*.cpp' | LC_ALL=C sort)
clang++ -std=c++11 -g -O1 -fno-exceptions -fno-rtti \
  -fsanitize=fuzzer,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined \
  -Ifirmware/src firmware/fuzz/fuzz_device.cpp "${library[@]}" -o "$out/fuzz_device"
if [ "$seconds" = "--build" ]; then exit 0; fi

# -max_len: a few dozen frames; -timeout: any input slower than 5 s is a hang.
status=0
"$out/fuzz_device" "$out/corpus" firmware/fuzz/corpus \
  -max_total_time="$seconds" -max_len=4096 -timeout=5 -print_final_stats=1 \
  -artifact_prefix="$out/" > "$out/last-run.log" 2>&1 || status=$?
grep -E "INITED|DONE|Done [0-9]+ runs|stat::number_of_executed_units|runtime error|ERROR|SUMMARY|invariant" "$out/last-run.log" || true
if [ "$status" -ne 0 ]; then
  echo "FAIL: the fuzzer found a problem (exit $status); see $out/last-run.log and the crash-* input in $out/"
  exit 1
fi
echo "fuzz: no crash, leak, sanitizer report or invariant violation in ${seconds} s"
