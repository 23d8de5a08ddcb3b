/**
 * Little-endian readers and writers for the wire's field types (docs/protocol.md
 * §2): u8, u16, u32, i32, f32, unsigned LEB128 varints of at most 5 bytes, and
 * short strings.
 */
export class WireFormatError extends Error {}

export class ByteWriter {
  private buf: Uint8Array;
  private view: DataView;
  length = 0;

  constructor(capacity = 64) {
    this.buf = new Uint8Array(capacity);
    this.view = new DataView(this.buf.buffer);
  }

  private room(n: number): void {
    if (this.length + n <= this.buf.length) return;
    const grown = new Uint8Array(Math.max(this.buf.length * 2, this.length + n));
    grown.set(this.buf);
    this.buf = grown;
    this.view = new DataView(grown.buffer);
  }

  u8(v: number): this {
    this.room(1);
    this.buf[this.length++] = v & 0xff;
    return this;
  }
  u16(v: number): this {
    this.room(2);
    this.view.setUint16(this.length, v, true);
    this.length += 2;
    return this;
  }
  u32(v: number): this {
    this.room(4);
    this.view.setUint32(this.length, v >>> 0, true);
    this.length += 4;
    return this;
  }
  i32(v: number): this {
    this.room(4);
    this.view.setInt32(this.length, v | 0, true);
    this.length += 4;
    return this;
  }
  f32(v: number): this {
    this.room(4);
    this.view.setFloat32(this.length, v, true);
    this.length += 4;
    return this;
  }
  varint(v: number): this {
    if (!Number.isInteger(v) || v < 0 || v > 0xffffffff) throw new WireFormatError(`varint out of range: ${v}`);
    let x = v;
    while (x >= 0x80) {
      this.u8((x & 0x7f) | 0x80);
      x = Math.floor(x / 128);
    }
    return this.u8(x);
  }
  str(s: string): this {
    if (s.length > 31 || !/^[\x20-\x7e]*$/.test(s)) throw new WireFormatError(`names are at most 31 printable ASCII bytes: ${JSON.stringify(s)}`);
    this.u8(s.length);
    for (let i = 0; i < s.length; i++) this.u8(s.charCodeAt(i));
    return this;
  }
  bytes(): Uint8Array {
    return this.buf.slice(0, this.length);
  }
}

export class ByteReader {
  private readonly view: DataView;
  offset: number;
  readonly end: number;

  constructor(
    readonly buf: Uint8Array,
    start = 0,
    end = buf.length,
  ) {
    this.view = new DataView(buf.buffer, buf.byteOffset, buf.byteLength);
    this.offset = start;
    this.end = end;
  }

  get remaining(): number {
    return this.end - this.offset;
  }
  private need(n: number): void {
    if (this.offset + n > this.end) throw new WireFormatError('payload too short');
  }
  u8(): number {
    this.need(1);
    return this.buf[this.offset++];
  }
  u16(): number {
    this.need(2);
    const v = this.view.getUint16(this.offset, true);
    this.offset += 2;
    return v;
  }
  u32(): number {
    this.need(4);
    const v = this.view.getUint32(this.offset, true);
    this.offset += 4;
    return v;
  }
  i32(): number {
    this.need(4);
    const v = this.view.getInt32(this.offset, true);
    this.offset += 4;
    return v;
  }
  f32(): number {
    this.need(4);
    const v = this.view.getFloat32(this.offset, true);
    this.offset += 4;
    return v;
  }
  varint(): number {
    let value = 0;
    let scale = 1;
    for (let i = 0; i < 5; i++) {
      const b = this.u8();
      value += (b & 0x7f) * scale;
      if ((b & 0x80) === 0) {
        if (value > 0xffffffff) throw new WireFormatError('varint over 32 bits');
        return value;
      }
      scale *= 128;
    }
    throw new WireFormatError('varint longer than 5 bytes');
  }
  str(): string {
    const n = this.u8();
    if (n > 31) throw new WireFormatError('name longer than 31 bytes');
    this.need(n);
    let s = '';
    for (let i = 0; i < n; i++) {
      const b = this.buf[this.offset + i];
      // the encoder's rule (str above): printable ASCII only, so a name can be shown and logged as is
      if (b < 0x20 || b > 0x7e) throw new WireFormatError(`name byte ${i} is 0x${b.toString(16).padStart(2, '0')}, not printable ASCII`);
      s += String.fromCharCode(b);
    }
    this.offset += n;
    return s;
  }
  /** Fails unless every byte was read. */
  done(): void {
    if (this.offset !== this.end) throw new WireFormatError(`${this.end - this.offset} bytes left over`);
  }
}
