// The message of the InputError a call throws, for tests of bad input at any layer.
#pragma once
#include "core/error.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace weft::test {

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

}  // namespace weft::test
