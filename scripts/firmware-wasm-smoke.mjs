#!/usr/bin/env node
// Smoke check of the firmware's wasm builds (scripts/firmware-wasm.sh):
// every module instantiates with the imports of firmware/WASM_ABI.md, runs
// its static constructors, setup() and loop(), and answers a HELLO_REQUEST
// with ACK, HELLO (its name) and its READERs. The Stepper module also runs a
// 1 mm move and must emit exactly 80 steps on its STEP pin (D2).
//
//   node scripts/firmware-wasm-smoke.mjs DIR Example...
import { readFileSync } from 'node:fs';
import path from 'node:path';

const [dir, ...examples] = process.argv.slice(2);
if (!dir || examples.length === 0) {
  console.error('usage: node scripts/firmware-wasm-smoke.mjs DIR Example...');
  process.exit(2);
}

// ---- a tiny author side: CRC-16/CCITT-FALSE, COBS, little-endian fields
function crc16(bytes) {
  let crc = 0xffff;
  for (const b of bytes) {
    crc ^= b << 8;
    for (let i = 0; i < 8; i++) crc = crc & 0x8000 ? ((crc << 1) ^ 0x1021) & 0xffff : (crc << 1) & 0xffff;
  }
  return crc;
}
function cobs(bytes) {
  const out = [0];
  let code = 0, codeAt = 0, n = 1;
  for (const b of bytes) {
    if (b === 0) { out[codeAt] = n; codeAt = out.length; out.push(0); n = 1; }
    else { out.push(b); n++; }
  }
  out[codeAt] = n;
  void code;
  return out;
}
function unCobs(frame) {
  const out = [];
  for (let i = 0; i < frame.length; ) {
    const code = frame[i++];
    for (let k = 1; k < code; k++) out.push(frame[i++]);
    if (code < 0xff && i < frame.length) out.push(0);
  }
  return out;
}
function frame(seq, type, payload) {
  const packet = [seq, type, ...payload];
  const crc = crc16(packet);
  return Uint8Array.from([...cobs([...packet, crc & 0xff, crc >> 8]), 0]);
}
const u16 = (v) => [v & 0xff, (v >> 8) & 0xff];
const u32 = (v) => [v & 0xff, (v >>> 8) & 0xff, (v >>> 16) & 0xff, (v >>> 24) & 0xff];
const f32 = (v) => [...new Uint8Array(new Float32Array([v]).buffer)];
const varint = (v) => { const o = []; while (v >= 0x80) { o.push((v & 0x7f) | 0x80); v >>>= 7; } o.push(v); return o; };

function packetsOf(bytes) {
  const packets = [];
  let current = [];
  for (const b of bytes) {
    if (b !== 0) { current.push(b); continue; }
    if (current.length === 0) continue;
    const p = unCobs(current);
    current = [];
    const crc = p[p.length - 2] | (p[p.length - 1] << 8);
    if (crc16(p.slice(0, -2)) !== crc) throw new Error('device sent a frame with a bad CRC');
    packets.push({ seq: p[0], type: p[1], payload: p.slice(2, -2) });
  }
  return packets;
}

// ---- one simulated board
async function load(file) {
  let clock = 1_000_000;
  let memory;
  const serial = [];
  const pins = [];
  const env = {
    maxl_micros: () => clock >>> 0,
    maxl_serial_write: (ptr, len) => serial.push(...new Uint8Array(memory.buffer, ptr, len)),
    maxl_pin_mode: () => {},
    maxl_digital_write: (pin, value) => pins.push({ t: clock, pin, value }),
    maxl_digital_read: () => 0,
    maxl_analog_write: () => {},
    maxl_led_show: () => {},
    maxl_i2c_write: () => 2, // nobody at the address
    maxl_i2c_read: () => 0,
    maxl_servo_pulse: () => {},
  };
  const { instance } = await WebAssembly.instantiate(readFileSync(file), { env });
  const ex = instance.exports;
  memory = ex.memory;
  ex.__wasm_call_ctors();
  ex.maxl_setup();
  ex.maxl_loop();
  return {
    ex, serial, pins,
    get clock() { return clock; },
    set clock(v) { clock = v; },
    send(bytes) {
      new Uint8Array(memory.buffer, ex.maxl_rx_buffer(), bytes.length).set(bytes);
      if (ex.maxl_rx_push(bytes.length) !== bytes.length) throw new Error('receive ring full');
      ex.maxl_loop();
    },
    take() { return packetsOf(serial.splice(0)); },
  };
}

const ACK = 0x43, HELLO = 0x41, READER = 0x42;
let failed = 0;
for (const name of examples) {
  const file = path.join(dir, `${name}.wasm`);
  try {
    const board = await load(file);
    board.send(frame(0, 0x01, [1]));
    const replies = board.take();
    if (replies[0]?.type !== ACK || replies[0].payload[0] !== 0) throw new Error('no ACK of the HELLO_REQUEST');
    const hello = replies[1];
    if (hello?.type !== HELLO) throw new Error('no HELLO');
    const deviceName = String.fromCharCode(...hello.payload.slice(12, 12 + hello.payload[11]));
    const readers = replies.slice(2).filter((p) => p.type === READER);
    if (readers.length !== hello.payload[10]) throw new Error(`HELLO says ${hello.payload[10]} readers, got ${readers.length} READERs`);
    const readerNames = readers.map((r) => String.fromCharCode(...r.payload.slice(4, 4 + r.payload[3])));
    let extra = '';
    if (name === 'Stepper') {
      // 1 mm in 10 ms at 80 steps/mm, from rest to rest: exactly 80 steps on D2.
      // Accelerate 5 ms then decelerate 5 ms: σ(T) = α·(d1²/2 + d1·d2 − d2²/2) = α·25e-6 s² = 1.
      board.send(frame(1, 0x04, [0, 1, 0])); // SUBSCRIBE reader 0, position, slot 0
      board.send(frame(2, 0x05, [...u16(0), 1, 1, ...u32(0), ...f32(1.0), ...u32(65536)])); // GEOMETRY with p0
      const start = board.clock + 1000;
      board.send(frame(3, 0x06, [...u16(0), 1, 1, ...f32(1000), ...u32(start), 0x0d, ...varint(5000), ...varint(5000), ...f32(40000)])); // TIMING
      const answers = board.take().filter((p) => p.type === ACK || p.type === 0x44);
      if (answers.some((p) => p.type !== ACK)) throw new Error('the move was refused');
      for (let t = board.clock; t < start + 12000; t += 20) { board.clock = t; board.ex.maxl_loop(); }
      const rising = board.pins.filter((w, i, all) => w.pin === 2 && w.value === 1 && !(all.slice(0, i).reverse().find((p) => p.pin === 2)?.value === 1)).length;
      if (rising !== 80) throw new Error(`expected 80 steps, got ${rising}`);
      if (!board.ex.maxl_idle()) throw new Error('not idle after the move');
      extra = `, a 1 mm move gave ${rising} steps`;
    }
    console.log(`${name}.wasm: instantiates; HELLO "${deviceName}" with readers ${readerNames.join(', ')}${extra}`);
  } catch (e) {
    failed++;
    console.error(`FAIL ${name}.wasm: ${e.message}`);
  }
}
process.exit(failed ? 1 : 0);
