#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace maxltest {
std::vector<uint8_t> fromHex(const std::string& hex);
std::string toHex(const std::vector<uint8_t>& bytes);
std::string toHex(const uint8_t* bytes, size_t n);
}  // namespace maxltest
