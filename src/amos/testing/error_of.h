#pragma once
// For tests: the message of the std::runtime_error a call throws ("" when it throws none), to check that an error
// names what is at fault.
#include <functional>
#include <stdexcept>
#include <string>

namespace amos::testing {

inline std::string errorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace amos::testing
