// The output directory's own files and its lock (see directory.hpp).
#include "emcontact/output/directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <utility>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/output/safe_temp.hpp"

namespace emc::output {
namespace {

bool is_owned(const std::string& name) {
  for (const char* f : {"monitors.csv", "checkpoint.h5", "fields.xdmf", "mesh.h5", "energies.png"})
    if (name == f) return true;
  return frame_step(name) >= 0;
}

/// `<owned name>.tmp.<random>` as create_temp() names it (`.png` after energies.png's): a
/// temporary of ours left by a killed run.
bool is_owned_temporary(const std::string& name) {
  const std::size_t at = name.find(".tmp.");
  if (at == std::string::npos) return false;
  const std::string target = name.substr(0, at);
  if (!is_owned(target)) return false;
  const std::string rest = name.substr(at + 5);
  const std::string suffix = target == "energies.png" ? ".png" : "";
  if (rest.size() != kTempRandomLength + suffix.size()) return false;
  if (rest.compare(kTempRandomLength, suffix.size(), suffix) != 0) return false;
  return std::all_of(rest.begin(), rest.begin() + kTempRandomLength,
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
}

}  // namespace

std::string frame_file_name(long step) {
  return format("fields_%08ld.h5", step);
}

long frame_step(const std::string& name) {
  const std::string prefix = "fields_", suffix = ".h5";
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0)
    return -1;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size() - suffix.size();
  long step = -1;
  const auto res = std::from_chars(first, last, step);
  if (res.ec != std::errc() || res.ptr != last || step < 0) return -1;
  return frame_file_name(step) == name ? step : -1;
}

std::vector<std::string> owned_files(const Directory& dir) {
  std::vector<std::string> owned;
  for (const auto& name : dir.entries())
    if (is_owned(name)) owned.push_back(name);
  return owned;
}

std::vector<std::string> owned_files(const std::string& dir) {
  return owned_files(Directory(dir, true));
}

double owned_bytes(const Directory& dir) {
  double bytes = 0;
  for (const auto& name : owned_files(dir)) {
    struct stat st {};
    if (::fstatat(dir.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode))
      bytes += static_cast<double>(st.st_size);
  }
  return bytes;
}

void remove_owned_files(const Directory& dir) {
  for (const auto& name : dir.entries()) {
    if (!is_owned(name) && !is_owned_temporary(name)) continue;
    struct stat st {};
    if (::fstatat(dir.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || S_ISDIR(st.st_mode))
      continue;
    if (::unlinkat(dir.fd(), name.c_str(), 0) != 0 && errno != ENOENT)
      throw Error("--overwrite: cannot remove '" + dir.path(name) + "': " + std::strerror(errno));
  }
}

void remove_owned_files(const std::string& dir) {
  remove_owned_files(Directory(dir, true));
}

DirectoryLock::DirectoryLock(const Directory& dir) {
  const std::string path = dir.path(".emcontact.lock");
  // O_NOFOLLOW: a link planted there is refused, never followed; O_NONBLOCK: a FIFO planted
  // there does not block the open (and is refused below)
  fd_ = ::openat(dir.fd(), ".emcontact.lock",
                 O_RDONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw Error("cannot lock the output directory '" + dir.path() + "': " + path + ": " +
                std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw Error("cannot lock the output directory '" + dir.path() + "': " + path +
                " is not a regular file");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK)
      throw Error("output directory '" + dir.path() + "' is in use by another emcontact run (" +
                  path + " is locked); wait for it or choose another --output");
    throw Error("cannot lock the output directory '" + dir.path() + "': " + std::strerror(err));
  }
}

DirectoryLock::DirectoryLock(const std::string& dir) : DirectoryLock(Directory(dir, true)) {}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

DirectoryLock::DirectoryLock(DirectoryLock&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

}  // namespace emc::output
