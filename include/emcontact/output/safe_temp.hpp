#pragma once
// Temporary files next to their target, created so that nobody else's file can be written
// through them: an unpredictable name, created exclusively (O_EXCL), never through a symbolic
// link (O_NOFOLLOW), not inherited by child processes (O_CLOEXEC).
#include <string>

namespace emc::output {

struct TempFile {
  int fd = -1;       ///< open for writing, owned by the caller
  std::string name;  ///< `<path>.tmp.<random>`, in the directory of `path`
};

/// Creates a fresh temporary for `path` (mode 0644 less the umask); throws emc::Error naming
/// `path` if it cannot.
TempFile create_temp(const std::string& path);

}  // namespace emc::output
