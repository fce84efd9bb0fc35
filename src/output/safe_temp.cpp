// Temporary files created exclusively under unpredictable names (see safe_temp.hpp).
#include "emcontact/output/safe_temp.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include "emcontact/error.hpp"

namespace emc::output {
namespace {

/// Twelve random letters and digits (71 bits): a name another user cannot plant in advance.
std::string random_suffix() {
  static const char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device rd;  // the kernel's random source
  std::uniform_int_distribution<int> pick(0, sizeof(kChars) - 2);
  std::string s(kTempRandomLength, 'x');
  for (char& c : s) c = kChars[pick(rd)];
  return s;
}

}  // namespace

TempFile create_temp(const Directory& dir, const std::string& name, const std::string& suffix) {
  constexpr int kFlags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC;
  int err = EEXIST;
  // A name that exists already (planted or left over) is skipped, never opened.
  for (int attempt = 0; attempt < 100 && err == EEXIST; ++attempt) {
    TempFile t;
    t.name = name + ".tmp." + random_suffix() + suffix;
    t.fd = ::openat(dir.fd(), t.name.c_str(), kFlags, 0644);
    if (t.fd >= 0) return t;
    err = errno;
    if (err == EINTR) err = EEXIST;  // try again
  }
  throw Error("cannot create a temporary file for '" + dir.path(name) + "': " + std::strerror(err));
}

}  // namespace emc::output
