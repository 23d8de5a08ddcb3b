// Little-endian reads and writes over a byte buffer, as docs/protocol.md §2
// defines them: u8, u16, u32, i32, f32, varint (unsigned LEB128, at most 5
// bytes, at most 2^32 - 1) and str (u8 length + ASCII).
//
// Both classes are bounds-checked and "sticky": the first read past the end,
// bad varint or over-long write sets `failed`, every later call is a no-op
// returning 0, and the caller checks once at the end.
#ifndef MAXL_WIRE_BYTES_H
#define MAXL_WIRE_BYTES_H

#include <stdint.h>
#include <string.h>

namespace maxl_fw {

class ByteReader {
 public:
  ByteReader(const uint8_t* data, uint8_t length) : data_(data), length_(length), pos_(0), failed_(false) {}

  uint8_t u8() {
    if (!need(1)) return 0;
    return data_[pos_++];
  }
  uint16_t u16() {
    if (!need(2)) return 0;
    uint16_t v = (uint16_t)(data_[pos_] | ((uint16_t)data_[pos_ + 1] << 8));
    pos_ += 2;
    return v;
  }
  uint32_t u32() {
    if (!need(4)) return 0;
    uint32_t v = (uint32_t)data_[pos_] | ((uint32_t)data_[pos_ + 1] << 8) | ((uint32_t)data_[pos_ + 2] << 16) |
                 ((uint32_t)data_[pos_ + 3] << 24);
    pos_ += 4;
    return v;
  }
  int32_t i32() { return (int32_t)u32(); }
  float f32() {
    uint32_t bits = u32();
    float f;
    memcpy(&f, &bits, 4);
    return f;
  }
  // Unsigned LEB128. A sixth byte, or bits above 2^32 - 1 in the fifth, fail.
  uint32_t varint() {
    uint32_t value = 0;
    for (uint8_t i = 0; i < 5; i++) {
      uint8_t b = u8();
      if (failed_) return 0;
      if (i == 4 && (b & 0xF0)) return fail();  // over 2^32 - 1, or a sixth byte
      value |= (uint32_t)(b & 0x7F) << (7 * i);
      if (!(b & 0x80)) return value;
    }
    return 0;  // not reached
  }
  // A str: returns a pointer into the buffer (not NUL-terminated) and its length.
  const char* str(uint8_t& length, uint8_t maxLength) {
    length = u8();
    if (failed_ || length > maxLength || !need(length)) {
      fail();
      length = 0;
      return 0;
    }
    const char* p = (const char*)(data_ + pos_);
    pos_ += length;
    return p;
  }
  void skip(uint8_t n) {
    if (need(n)) pos_ += n;
  }

  bool failed() const { return failed_; }
  uint8_t position() const { return pos_; }
  uint8_t remaining() const { return (uint8_t)(length_ - pos_); }
  bool atEnd() const { return !failed_ && pos_ == length_; }
  uint32_t fail() {
    failed_ = true;
    return 0;
  }

 private:
  bool need(uint8_t n) {
    if (failed_) return false;
    if ((uint16_t)pos_ + n > length_) {
      failed_ = true;
      return false;
    }
    return true;
  }
  const uint8_t* data_;
  uint8_t length_;
  uint8_t pos_;
  bool failed_;
};

class ByteWriter {
 public:
  ByteWriter(uint8_t* data, uint8_t capacity) : data_(data), capacity_(capacity), pos_(0), failed_(false) {}

  void u8(uint8_t v) {
    if (need(1)) data_[pos_++] = v;
  }
  void u16(uint16_t v) {
    if (!need(2)) return;
    data_[pos_++] = (uint8_t)v;
    data_[pos_++] = (uint8_t)(v >> 8);
  }
  void u32(uint32_t v) {
    if (!need(4)) return;
    data_[pos_++] = (uint8_t)v;
    data_[pos_++] = (uint8_t)(v >> 8);
    data_[pos_++] = (uint8_t)(v >> 16);
    data_[pos_++] = (uint8_t)(v >> 24);
  }
  void i32(int32_t v) { u32((uint32_t)v); }
  void f32(float f) {
    uint32_t bits;
    memcpy(&bits, &f, 4);
    u32(bits);
  }
  void varint(uint32_t v) {
    while (v >= 0x80) {
      u8((uint8_t)(v | 0x80));
      v >>= 7;
    }
    u8((uint8_t)v);
  }
  void str(const char* s, uint8_t length) {
    u8(length);
    if (!need(length)) return;
    memcpy(data_ + pos_, s, length);
    pos_ += length;
  }
  // A NUL-terminated name, cut at MAX_NAME (31) bytes.
  void name(const char* s) {
    uint8_t n = 0;
    while (s && s[n] && n < 31) n++;
    str(s, n);
  }

  bool failed() const { return failed_; }
  uint8_t length() const { return pos_; }
  uint8_t remaining() const { return (uint8_t)(capacity_ - pos_); }

  static uint8_t varintSize(uint32_t v) {
    uint8_t n = 1;
    while (v >= 0x80) {
      v >>= 7;
      n++;
    }
    return n;
  }

 private:
  bool need(uint8_t n) {
    if (failed_) return false;
    if ((uint16_t)pos_ + n > capacity_) {
      failed_ = true;
      return false;
    }
    return true;
  }
  uint8_t* data_;
  uint8_t capacity_;
  uint8_t pos_;
  bool failed_;
};

}  // namespace maxl_fw

#endif
