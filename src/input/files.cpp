#include "emcontact/input/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "emcontact/error.hpp"

namespace emc::input {
namespace {

std::string kind_of(mode_t m) {
  if (S_ISDIR(m)) return "it is a directory, not a regular file";
  if (S_ISFIFO(m)) return "it is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(m) || S_ISBLK(m)) return "it is a device, not a regular file";
  if (S_ISSOCK(m)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

}  // namespace

void check_regular_file(const std::string& path, const std::string& what) {
  const std::string head = path + ": cannot read the " + what + ": ";
  if (path.empty()) throw InputError("cannot read the " + what + ": the file name is empty");
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    throw InputError(head + (errno == ENOENT ? "no such file" : std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw InputError(head + kind_of(st.st_mode));
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(head + std::strerror(errno));
  close(fd);
}

}  // namespace emc::input
