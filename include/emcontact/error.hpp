#pragma once
// One exception type for every user-facing failure: it names where (file, parameter path,
// element id) and what is allowed. main() prints it on rank 0 and exits non-zero.
#include <stdexcept>
#include <string>

namespace emc {
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};
/// Bad user input: a parameter, a file, a mesh. Raised before any work is done.
class InputError : public Error {
 public:
  explicit InputError(const std::string& what) : Error(what) {}
};
/// A failure during the run (linear solver, Newton, inverted element) that cannot be recovered.
class RunError : public Error {
 public:
  explicit RunError(const std::string& what) : Error(what) {}
};
}  // namespace emc
