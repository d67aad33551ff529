// Errors about the user's input: the message names the file (or scene) and the element.
#pragma once
#include <stdexcept>
#include <string>

namespace weft {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace weft
