// Atomic file replacement (a safely created temp file + fsync + rename) and `mkdir -p`.
#include "emcontact/output/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "emcontact/error.hpp"
#include "emcontact/output/safe_temp.hpp"

namespace emc::output {
namespace {

/// "what 'path': strerror(err)" as an emc::Error.
Error os_error(const std::string& what, const std::string& path, int err) {
  return Error(what + " '" + path + "': " + std::strerror(err));
}

/// Writes all of `content` to `fd`, retrying on EINTR and short writes. Returns 0 or errno.
int write_all(int fd, const std::string& content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

/// Best effort: makes the rename itself durable. Failure here is not an error (some file
/// systems refuse fsync on directories) since the data was already synced.
void sync_directory(const Directory& dir) {
  (void)::fsync(dir.fd());
}

}  // namespace

/// The directory part of `path` ("." if it has none).
std::string parent_directory(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

void atomic_write(const Directory& dir, const std::string& name, const std::string& content) {
  TempFile tmp = create_temp(dir, name);
  const int err = write_all(tmp.fd, content);
  if (err != 0) {
    discard_temp(dir, tmp);
    throw os_error("cannot write", dir.path(name), err);
  }
  commit_temp(dir, tmp, name);
}

void atomic_write(const std::string& path, const std::string& content) {
  atomic_write(directory_of(path), base_name(path), content);
}

Directory directory_of(const std::string& path) {
  const std::string dir = parent_directory(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) throw os_error("cannot write", path, errno);
  if (!S_ISDIR(st.st_mode)) throw os_error("cannot write", path, ENOTDIR);
  return Directory(dir, true);
}

void commit_temp(const Directory& dir, TempFile& tmp, const std::string& name) {
  int err = ::fsync(tmp.fd) != 0 ? errno : 0;
  if (::close(tmp.fd) != 0 && err == 0) err = errno;
  tmp.fd = -1;
  // renameat replaces a link planted at `name` itself, never the file it points to
  if (err == 0 && ::renameat(dir.fd(), tmp.name.c_str(), dir.fd(), name.c_str()) != 0) err = errno;
  if (err != 0) {
    discard_temp(dir, tmp);
    throw os_error("cannot write", dir.path(name), err);
  }
  sync_directory(dir);
}

void discard_temp(const Directory& dir, TempFile& tmp) {
  if (tmp.fd >= 0) ::close(tmp.fd);
  tmp.fd = -1;
  ::unlinkat(dir.fd(), tmp.name.c_str(), 0);
}

void make_directory(const std::string& dir) {
  if (dir.empty()) return;
  // Create every prefix ending before a '/', then the whole path (mkdir -p).
  for (std::size_t pos = dir.find('/', 1);; pos = dir.find('/', pos + 1)) {
    const std::string prefix = dir.substr(0, pos);
    if (::mkdir(prefix.c_str(), 0755) != 0 && errno != EEXIST) {
      throw os_error("cannot create directory", dir, errno);
    }
    if (pos == std::string::npos) break;
  }
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) throw os_error("cannot create directory", dir, errno);
  if (!S_ISDIR(st.st_mode)) throw os_error("cannot create directory", dir, ENOTDIR);
}

GrowingFile::~GrowingFile() {
  if (fd_ < 0) return;
  (void)::fsync(fd_);  // best effort: the writers sync() where it matters
  ::close(fd_);
}

GrowingFile::GrowingFile(GrowingFile&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)), size_(o.size_), path_(std::move(o.path_)) {}

GrowingFile& GrowingFile::operator=(GrowingFile&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
    size_ = o.size_;
    path_ = std::move(o.path_);
  }
  return *this;
}

void GrowingFile::replace(const Directory& dir, const std::string& name,
                          const std::string& content) {
  atomic_write(dir, name, content);
  if (fd_ >= 0) ::close(fd_);
  path_ = dir.path(name);
  fd_ = ::openat(dir.fd(), name.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd_ < 0) throw os_error("cannot write", path_, errno);
  size_ = content.size();
}

void GrowingFile::write_at(std::size_t offset, const std::string& text) {
  if (fd_ < 0 || offset > size_) throw Error("cannot write '" + path_ + "': not open at that end");
  const char* p = text.data();
  std::size_t left = text.size(), at = offset;
  int err = 0;
  while (left > 0 && err == 0) {
    const ssize_t n = ::pwrite(fd_, p, left, static_cast<off_t>(at));
    if (n < 0) {
      if (errno != EINTR) err = errno;
      continue;
    }
    p += n;
    at += static_cast<std::size_t>(n);
    left -= static_cast<std::size_t>(n);
  }
  if (err == 0 && offset + text.size() < size_ &&
      ::ftruncate(fd_, static_cast<off_t>(offset + text.size())) != 0)
    err = errno;
  if (err != 0) {
    (void)::ftruncate(fd_, static_cast<off_t>(size_));  // what was written beyond the old end
    throw os_error("cannot write", path_, err);
  }
  size_ = offset + text.size();
}

void GrowingFile::sync() const {
  if (fd_ >= 0 && ::fsync(fd_) != 0) throw os_error("cannot write", path_, errno);
}

}  // namespace emc::output
