#include "support/hex.h"

#include <stdexcept>

namespace maxltest {

std::vector<uint8_t> fromHex(const std::string& hex) {
  std::vector<uint8_t> out;
  std::string digits;
  for (char c : hex)
    if (!isspace((unsigned char)c)) digits += c;
  if (digits.size() % 2) throw std::runtime_error("odd hex length: " + hex);
  for (size_t i = 0; i < digits.size(); i += 2) out.push_back((uint8_t)std::stoul(digits.substr(i, 2), nullptr, 16));
  return out;
}

std::string toHex(const uint8_t* bytes, size_t n) {
  static const char* d = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < n; i++) {
    s += d[bytes[i] >> 4];
    s += d[bytes[i] & 15];
  }
  return s;
}

std::string toHex(const std::vector<uint8_t>& bytes) { return toHex(bytes.data(), bytes.size()); }

}  // namespace maxltest
