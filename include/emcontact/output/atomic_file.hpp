#pragma once
#include <cstddef>
#include <string>

#include "emcontact/output/open_directory.hpp"
#include "emcontact/output/safe_temp.hpp"

namespace emc::output {
/// Writes `content` to the file `name` of `dir` atomically: a temporary file in `dir`, fsync,
/// then renameat, so a killed run leaves either the old or the new complete file. Throws
/// emc::Error naming dir.path(name); the file is then unchanged and no temporary is left.
void atomic_write(const Directory& dir, const std::string& name, const std::string& content);
/// The same for `path`, its directory opened by name first.
void atomic_write(const std::string& path, const std::string& content);
/// Completes a temporary of `dir` whose content was written through tmp.fd: fsync, close, then
/// renameat to `name`. On failure removes the temporary and throws emc::Error naming
/// dir.path(name).
void commit_temp(const Directory& dir, TempFile& tmp, const std::string& name);
/// Closes and removes a temporary of `dir` that is not wanted (best effort).
void discard_temp(const Directory& dir, TempFile& tmp);
/// The directory of the file `path`, opened by name (links followed); throws emc::Error
/// "cannot write '<path>': <reason>" if there is none.
Directory directory_of(const std::string& path);
/// The directory part of `path` ("." if it has none, "/" for a file in the root).
std::string parent_directory(const std::string& path);
/// Creates the directory (and parents) or throws emc::Error naming it.
void make_directory(const std::string& dir);

/// A file that grows by small writes (the monitors' rows, the fields index's frames), so that
/// a long run costs O(new text) per write, never a rewrite of the whole file: replace() writes
/// it whole (atomic_write) and holds it open; write_at() then writes over its end. A write that
/// fails (a full disk) cuts the file back to its size before the write, so it stays whole.
class GrowingFile {
 public:
  GrowingFile() = default;
  ~GrowingFile();
  GrowingFile(GrowingFile&& o) noexcept;
  GrowingFile& operator=(GrowingFile&& o) noexcept;
  GrowingFile(const GrowingFile&) = delete;
  GrowingFile& operator=(const GrowingFile&) = delete;

  /// The file `name` of `dir` replaced by `content` (atomic_write), then opened for writing
  /// (never through a link planted in its place).
  void replace(const Directory& dir, const std::string& name, const std::string& content);
  /// Writes `text` at byte `offset` (at most size()): the file then ends with it. On failure the
  /// file is cut back to its previous size (the bytes from `offset` on may have changed) and
  /// emc::Error names it.
  void write_at(std::size_t offset, const std::string& text);
  /// fsync: the writes so far are on disk. Throws emc::Error naming the file.
  void sync() const;
  bool is_open() const { return fd_ >= 0; }
  std::size_t size() const { return size_; }

 private:
  int fd_ = -1;
  std::size_t size_ = 0;
  std::string path_;  // for messages
};
}  // namespace emc::output
