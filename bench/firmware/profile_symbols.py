#!/usr/bin/env python3
"""Maps the harness's program-counter samples (BENCH_PROFILE) to functions.

    BENCH_PROFILE=/tmp/pc.txt simavr_steps FILE.elf RATE
    python3 bench/firmware/profile_symbols.py FILE.elf /tmp/pc.txt
"""
import bisect
import subprocess
import sys

elf, samples = sys.argv[1], sys.argv[2]
symbols = []
for line in subprocess.run(['avr-nm', '-n', '-C', elf], capture_output=True, text=True).stdout.splitlines():
    parts = line.split(' ', 2)
    if len(parts) == 3 and parts[0] and parts[1] in 'tTwW':
        symbols.append((int(parts[0], 16), parts[2]))
addresses = [a for a, _ in symbols]
totals = {}
count = 0
for line in open(samples):
    pc, n = map(int, line.split())
    i = bisect.bisect_right(addresses, pc) - 1
    name = symbols[i][1] if i >= 0 else '?'
    totals[name] = totals.get(name, 0) + n
    count += n
for name, n in sorted(totals.items(), key=lambda kv: -kv[1])[:25]:
    print(f'{100.0 * n / count:6.1f}%  {name}')
