#!/usr/bin/env python3
"""Seed inputs for fuzz_device.cpp, in its operation format: a session, a
subscription of each reader kind, geometry, timing, events and the running of
the loop, so that fuzzing starts deep in the handlers and the motion code.

    python3 firmware/fuzz/make_seeds.py
"""
import os
import struct

TYPE = {'HELLO_REQUEST': 0, 'PING': 1, 'CLOCK': 2, 'SUBSCRIBE': 3, 'GEOMETRY': 4, 'TIMING': 5,
        'EVENTS': 6, 'REPLACE_TAIL': 7, 'HALT': 8, 'STATUS_REQUEST': 9}  # indices into TYPES[]


def frame(kind, payload):
    return bytes([1, 0x00, TYPE[kind], len(payload)]) + payload  # op 1, in-order seq


def loops(n, dt):
    return bytes([3, n, dt])


def advance(us):
    return bytes([2, 2]) + struct.pack('<I', us)


f32 = lambda v: struct.pack('<f', v)
u16 = lambda v: struct.pack('<H', v)
u32 = lambda v: struct.pack('<I', v)
i32 = lambda v: struct.pack('<i', v)

hello = frame('HELLO_REQUEST', b'\x01')
sub = lambda reader, kind, slot: frame('SUBSCRIBE', bytes([reader, kind, slot]))
# readers: 0 a, 1 b (steppers), 2 x, 3 v, 4 acc, 5 e0, 6 e1, 7 s
subs = sub(0, 1, 0) + sub(1, 1, 1) + sub(3, 2, 0) + sub(4, 3, 0) + sub(5, 4, 0) + sub(7, 5, 0)
geometry = frame('GEOMETRY', u16(0) + bytes([2, 1]) + i32(0) + i32(0)
                 + f32(10.0) + i32(655360) + i32(-327680) + f32(5.0) + i32(983040) + i32(0))
start = 0xFFF00000 + 20000
timing = frame('TIMING', u16(0) + bytes([1, 1]) + f32(2000.0) + u32(start)
               + bytes([0x39]) + bytes([0xd0, 0x86, 0x03]) + bytes([0xa0, 0x9c, 0x01]) + bytes([0xd0, 0x86, 0x03]) + f32(20.0))
events = frame('EVENTS', u16(0) + bytes([0]) + u16(0) + bytes([2]) + bytes([0]) + f32(1.0) + bytes([0xe8, 0x07]) + f32(0.0))

# A dwell (length 0, p1 = where it starts) between two segments; timed as one cruise
# phase of 120 ms at alpha 0, then an instant (0 µs) of length 0 after the last.
dwell_geometry = frame('GEOMETRY', u16(0) + bytes([4, 1]) + i32(0) + i32(0)
                       + f32(10.0) + i32(655360) + i32(-327680) + f32(0.0) + i32(655360) + i32(-327680)
                       + f32(5.0) + i32(983040) + i32(0) + f32(0.0) + i32(983040) + i32(0))
dwell_timing = frame('TIMING', u16(0) + bytes([4, 1]) + f32(2000.0) + u32(start)
                     + bytes([0x39]) + bytes([0xd0, 0x86, 0x03]) + bytes([0xa0, 0x9c, 0x01]) + bytes([0xd0, 0x86, 0x03]) + f32(20.0)
                     + bytes([0x02]) + bytes([0xc0, 0xa9, 0x07]) + f32(0.0)
                     + bytes([0x39]) + bytes([0xd0, 0x86, 0x03]) + bytes([0xa0, 0x9c, 0x01]) + bytes([0xd0, 0x86, 0x03]) + f32(40.0)
                     + bytes([0x02, 0x00]) + f32(0.0))
dwell_events = frame('EVENTS', u16(1) + bytes([0]) + u16(0) + bytes([2]) + bytes([0]) + f32(1.0) + bytes([0xe0, 0xd4, 0x03]) + f32(0.5))

seeds = {
    'dwell': hello + subs + dwell_geometry + dwell_timing + dwell_events + loops(16, 255) + advance(300000) + loops(16, 200) + advance(300000) + loops(4, 10),
    # timing for the first segment only, ending at speed: braking passes the provisional dwell
    'dwell-starve': hello + subs + dwell_geometry + frame('TIMING', u16(0) + bytes([1, 1]) + f32(500.0) + u32(start) + bytes([0x02, 0x90, 0x4e]) + f32(0.0)) + advance(200000) + loops(8, 255),
    'session': hello + subs,
    'move': hello + subs + geometry + timing + events + loops(16, 255) + advance(100000) + loops(16, 200),
    'starve': hello + subs + geometry + frame('TIMING', u16(0) + bytes([1, 1]) + f32(500.0) + u32(start) + bytes([0x02, 0x90, 0x4e]) + f32(0.0)) + advance(200000) + loops(8, 255),
    'halt': hello + subs + geometry + timing + advance(30000) + frame('HALT', bytes([1]) + u32(start + 40000)) + advance(100000) + loops(4, 10),
    'replace': hello + subs + geometry + timing + frame('REPLACE_TAIL', u16(1)) + frame('STATUS_REQUEST', b''),
    'ping-clock': hello + frame('PING', u16(7) + u16(300)) + frame('CLOCK', u32(1) + u32(2) + i32(-300)),
    'raw-garbage': bytes([0, 40]) + bytes(range(1, 41)) + bytes([0, 2, 0, 0]),
}
here = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus')
os.makedirs(here, exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join(here, name), 'wb') as out:
        out.write(data)
print('seeds:', ', '.join(f'{k} ({len(v)} bytes)' for k, v in seeds.items()))
