// Checks the io_* and cli_* topics share: messages that contain a part, the InputError a call throws,
// attribute maps that are equal, a PNG's size.
#pragma once
#include "core/error.hpp"
#include "io/houdini_geo.hpp"
#include "tests/input_error_fixture.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

namespace weft::test {

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

inline void expect_same_attributes(const io::AttributeMap& a, const io::AttributeMap& b, const std::string& cls) {
  ASSERT_EQ(a.size(), b.size()) << cls;
  for (const auto& [name, x] : a) {
    ASSERT_TRUE(b.count(name)) << cls << " attribute " << name;
    const io::Attribute& y = b.at(name);
    EXPECT_EQ(x.storage, y.storage) << name;
    EXPECT_EQ(x.size, y.size) << name;
    EXPECT_EQ(x.qualifier, y.qualifier) << name;
    EXPECT_EQ(x.floats, y.floats) << name;
    EXPECT_EQ(x.ints, y.ints) << name;
    EXPECT_EQ(x.strings, y.strings) << name;
  }
}

// Width and height from a PNG's signature and IHDR chunk; {0, 0} when the file is not a PNG.
inline std::pair<int, int> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[24] = {};
  if (!in.read(reinterpret_cast<char*>(b), 24)) return {0, 0};
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::memcmp(b, signature, 8) != 0 || std::memcmp(b + 12, "IHDR", 4) != 0) return {0, 0};
  const auto be32 = [&](int at) { return int(b[at]) << 24 | int(b[at + 1]) << 16 | int(b[at + 2]) << 8 | int(b[at + 3]); };
  return {be32(16), be32(20)};
}

}  // namespace weft::test
