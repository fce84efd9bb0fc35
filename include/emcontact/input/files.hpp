#pragma once
// Files named by the user (the input, a mesh, a checkpoint) must be regular files: a FIFO
// blocks the reader forever, a directory or a device (/dev/zero) is never what was meant.
// Header only (its messages echo the path with input::echo, of the input library, which the
// mesh and output modules that use it link).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::input {
namespace detail {

inline std::string kind_of(mode_t m) {
  if (S_ISDIR(m)) return "it is a directory, not a regular file";
  if (S_ISFIFO(m)) return "it is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(m) || S_ISBLK(m)) return "it is a device, not a regular file";
  if (S_ISSOCK(m)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

}  // namespace detail

/// Throws InputError "<path>: cannot read the <what>: <reason>" (the path echoed) unless `path` is
/// a regular file this process can read (reasons: no such file, it is a directory / FIFO / device /
/// not a regular file, or the open error).
inline void check_regular_file(const std::string& path, const std::string& what) {
  const std::string head = echo(path) + ": cannot read the " + what + ": ";
  if (path.empty()) throw InputError("cannot read the " + what + ": the file name is empty");
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    throw InputError(head + (errno == ENOENT ? "no such file" : std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw InputError(head + detail::kind_of(st.st_mode));
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(head + std::strerror(errno));
  close(fd);
}

}  // namespace emc::input
