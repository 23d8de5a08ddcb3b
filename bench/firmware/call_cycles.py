#!/usr/bin/env python3
"""Cycles per call of named functions during a step-rate run (BENCH_CALLS).

    python3 bench/firmware/call_cycles.py FILE.elf RATE_HZ NAME [NAME ...]

Runs the simavr step-rate harness (firmware/build/bench/simavr_steps, built by
`npm run bench -- firmware`) on FILE.elf at RATE_HZ with the environment as
given (STEPPERS, ANGLE_DEG, CRUISE_SEGMENTS, BENCH_PROFILE_FROM_US and
BENCH_PROFILE_TO_US to look at one span of device time, e.g. a ramp), and
prints, for each function whose demangled name contains NAME (the first
match), its calls and mean cycles per call: callees included, interrupts
excluded (for an interrupt vector, its own cycles).
"""
import os
import subprocess
import sys

if len(sys.argv) < 4:
    sys.exit(__doc__)
elf, rate, names = sys.argv[1], sys.argv[2], sys.argv[3:]
root = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
harness = os.path.join(root, 'firmware', 'build', 'bench', 'simavr_steps')

symbols = []
for line in subprocess.run(['avr-nm', '-C', elf], capture_output=True, text=True, check=True).stdout.splitlines():
    parts = line.split(' ', 2)
    if len(parts) == 3 and parts[0] and parts[1] in 'tTwW':
        symbols.append((int(parts[0], 16), parts[2]))
chosen = []
for name in names:
    match = next(((a, n) for a, n in symbols if name in n), None)
    if match is None:
        sys.exit(f'no function named like "{name}" in {elf}')
    chosen.append(match)

env = dict(os.environ, BENCH_CALLS=','.join(f'{a:x}' for a, _ in chosen))
run = subprocess.run([harness, elf, rate], env=env, capture_output=True, text=True)
if run.returncode != 0:
    sys.exit(f'the harness failed ({run.returncode}):\n{run.stderr}')
counts = {}
for line in run.stderr.splitlines():
    if line.startswith('calls '):
        _, addr, calls, _, cycles = line.split()
        counts[int(addr, 16)] = (int(calls), int(cycles))
print(run.stdout.strip().splitlines()[-1])
print(f'{"calls":>8} {"cycles/call":>12}  function')
for addr, name in chosen:
    calls, cycles = counts.get(addr, (0, 0))
    mean = f'{cycles / calls:.0f}' if calls else '-'
    print(f'{calls:>8} {mean:>12}  {name}')
