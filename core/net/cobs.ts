/**
 * Consistent Overhead Byte Stuffing (Cheshire and Baker, 1999). The encoding has no
 * zero bytes, so a 0x00 can end each frame. Each code byte k (1…255) says: k − 1
 * data bytes follow, then a zero, except after a code of 255 or at the end of the
 * frame, where no zero is implied.
 */
export function cobsEncode(data: Uint8Array): Uint8Array {
  const out = new Uint8Array(data.length + Math.ceil(data.length / 254) + 1);
  let codeAt = 0;
  let code = 1;
  let o = 1;
  for (let i = 0; i < data.length; i++) {
    if (data[i] === 0) {
      out[codeAt] = code;
      codeAt = o++;
      code = 1;
    } else {
      out[o++] = data[i];
      code++;
      if (code === 0xff) {
        out[codeAt] = code;
        // Canonical COBS: a full block at the very end is not followed by an empty one.
        if (i + 1 === data.length) return out.subarray(0, o);
        codeAt = o++;
        code = 1;
      }
    }
  }
  out[codeAt] = code;
  return out.subarray(0, o);
}

/** Decodes one COBS frame (without its delimiter). Returns null if a code byte points past the end. */
export function cobsDecode(frame: Uint8Array): Uint8Array | null {
  const out = new Uint8Array(frame.length);
  let o = 0;
  let i = 0;
  while (i < frame.length) {
    const code = frame[i++];
    if (code === 0) return null; // a zero can only be the delimiter
    const end = i + code - 1;
    if (end > frame.length) return null;
    while (i < end) {
      const b = frame[i++];
      if (b === 0) return null;
      out[o++] = b;
    }
    if (code !== 0xff && i < frame.length) out[o++] = 0;
  }
  return out.subarray(0, o);
}
