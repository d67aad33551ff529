// Checks the io_* topics share: messages that contain a part, the InputError a call throws, attribute maps
// that are equal.
#pragma once
#include "core/error.hpp"
#include "io/houdini_geo.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace weft::test {

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The message of the InputError f throws; a test failure (and "") when it throws none.
inline std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

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

}  // namespace weft::test
