// A directory held open by a descriptor (see open_directory.hpp).
#include "emcontact/output/open_directory.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "emcontact/error.hpp"

namespace emc::output {
namespace {

/// `path` without trailing "/" and "/." ("/" itself kept): "lnk/" and "lnk/." name the link
/// lnk itself, which the kernel would resolve before O_NOFOLLOW or lstat() saw it.
std::string without_trailing_slashes(std::string path) {
  for (;;) {
    if (path.size() > 1 && path.back() == '/')
      path.pop_back();
    else if (path.size() > 2 && path.compare(path.size() - 2, 2, "/.") == 0)
      path.resize(path.size() - 2);
    else
      return path;
  }
}

}  // namespace

Directory::Directory(const std::string& given, bool follow_link)
    : path_(without_trailing_slashes(given)) {
  const std::string& path = path_;
  const int flags = O_RDONLY | O_DIRECTORY | O_CLOEXEC | (follow_link ? 0 : O_NOFOLLOW);
  fd_ = ::open(path.c_str(), flags);
  if (fd_ >= 0) return;
  const int err = errno;
  struct stat st {};  // O_NOFOLLOW with O_DIRECTORY fails on a link with ENOTDIR or ELOOP
  if (!follow_link && ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
    throw Error("cannot open the directory '" + path +
                "': it is a symbolic link (give the directory it points to)");
  throw Error("cannot open the directory '" + path + "': " + std::strerror(err));
}

Directory::~Directory() {
  if (fd_ >= 0) ::close(fd_);
}

Directory::Directory(const Directory& o) : path_(o.path_) {
  if (o.fd_ < 0) return;
  fd_ = ::fcntl(o.fd_, F_DUPFD_CLOEXEC, 0);
  if (fd_ < 0) throw Error("cannot open the directory '" + path_ + "': " + std::strerror(errno));
}

Directory& Directory::operator=(const Directory& o) {
  if (this != &o) *this = Directory(o);
  return *this;
}

Directory::Directory(Directory&& o) noexcept
    : fd_(std::exchange(o.fd_, -1)), path_(std::move(o.path_)) {}

Directory& Directory::operator=(Directory&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
    path_ = std::move(o.path_);
  }
  return *this;
}

std::vector<std::string> Directory::entries() const {
  // a descriptor of its own: readdir moves the offset, which a dup would share
  const int fd = ::openat(fd_, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR* d = fd < 0 ? nullptr : ::fdopendir(fd);
  if (d == nullptr) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    throw Error("cannot list '" + path_ + "': " + std::strerror(err));
  }
  std::vector<std::string> names;
  while (const dirent* e = ::readdir(d)) names.emplace_back(e->d_name);
  ::closedir(d);
  std::sort(names.begin(), names.end());
  return names;
}

std::string base_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace emc::output
