// The message of the InputError (or a kind derived from it) a call throws, for tests of bad input at any layer.
#pragma once
#include "core/error.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace weft::test {

// The message of the error of kind E (an InputError or one derived from it) that f throws; a test failure
// (and "") when it throws none.
template <class E>
std::string thrown_message(const std::function<void()>& f, const char* kind) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no " << kind << " thrown";
  return "";
}

inline std::string input_error(const std::function<void()>& f) { return thrown_message<InputError>(f, "InputError"); }

}  // namespace weft::test
