#pragma once
// The message of the std::invalid_argument a call throws: how the tests
// check what a bad input (a parameter, an option, a file) is told.
#include <stdexcept>
#include <string>

namespace oit::test {

// The message of the std::invalid_argument `call` throws ("" when it does not).
template <typename Call>
std::string error_of(Call call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace oit::test
