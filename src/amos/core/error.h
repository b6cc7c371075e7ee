#pragma once
// One error style for the whole library: throw amos::core::Error with a message that names the file, line or
// option at fault. Library code never calls exit() or abort(); the app turns an Error into a message and exit code.
#include <stdexcept>
#include <string>

namespace amos::core {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error(message) when condition is false. For input validation, not for internal invariants.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace amos::core
