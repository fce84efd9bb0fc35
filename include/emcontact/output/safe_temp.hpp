#pragma once
// Temporary files next to their target, created so that nobody else's file can be written
// through them: an unpredictable name, created exclusively (O_EXCL), never through a symbolic
// link (O_NOFOLLOW), not inherited by child processes (O_CLOEXEC).
#include <cstddef>
#include <string>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// The length of the random part of a temporary's name (letters and digits).
inline constexpr std::size_t kTempRandomLength = 12;

struct TempFile {
  int fd = -1;       ///< open for writing, owned by the caller
  std::string name;  ///< `<name>.tmp.<random>`, in the directory it was created in
};

/// Creates a fresh temporary `<name>.tmp.<random><suffix>` for the file `name` of `dir` (mode
/// 0644 less the umask); throws emc::Error naming dir.path(name) if it cannot.
TempFile create_temp(const Directory& dir, const std::string& name, const std::string& suffix = "");

}  // namespace emc::output
