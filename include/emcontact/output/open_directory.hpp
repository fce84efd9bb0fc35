#pragma once
// A directory held open: a run creates, replaces, lists and removes its files relative to the
// descriptor (openat, renameat, unlinkat, fstatat), so renaming the directory or planting a
// link at its name after it was opened redirects nothing.
#include <string>
#include <vector>

namespace emc::output {

class Directory {
 public:
  Directory() = default;
  /// Opens the directory `path` (O_DIRECTORY; unless `follow_link`, O_NOFOLLOW: a symbolic link
  /// as its last component is refused). Throws emc::Error naming `path`.
  explicit Directory(const std::string& path, bool follow_link = false);
  ~Directory();
  Directory(const Directory& o);  ///< its own descriptor (dup), to the same directory
  Directory& operator=(const Directory& o);
  Directory(Directory&& o) noexcept;
  Directory& operator=(Directory&& o) noexcept;

  int fd() const { return fd_; }
  bool is_open() const { return fd_ >= 0; }
  /// The name it was opened by (messages only: it may name another directory by now).
  const std::string& path() const { return path_; }
  /// "<path>/<name>", for messages.
  std::string path(const std::string& name) const { return path_ + "/" + name; }
  /// The names of its entries (with "." and ".."), sorted; throws emc::Error naming it.
  std::vector<std::string> entries() const;

 private:
  int fd_ = -1;
  std::string path_;
};

/// The last component of `path` ("f" for "a/b/f"; `path` itself without a '/').
std::string base_name(const std::string& path);

}  // namespace emc::output
