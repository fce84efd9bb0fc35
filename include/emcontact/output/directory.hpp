#pragma once
// The output directory's own files: which of them a directory holds, removing exactly those
// (--overwrite), and the lock that keeps two runs out of one directory.
#include <string>
#include <vector>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// The names in `dir` of files an emcontact run writes there: monitors.csv, checkpoint.h5,
/// fields.xdmf, fields_<step>.h5, mesh.h5, energies.png (sorted).
std::vector<std::string> owned_files(const Directory& dir);
std::vector<std::string> owned_files(const std::string& dir);

/// Removes the owned files of `dir` and the temporaries left by a killed writer; never any
/// other file, never a directory. Throws emc::Error naming a file it cannot remove.
void remove_owned_files(const Directory& dir);
void remove_owned_files(const std::string& dir);

/// An exclusive lock on DIR/.emcontact.lock (flock), held while the object lives.
class DirectoryLock {
 public:
  DirectoryLock() = default;
  /// Takes the lock at once or throws emc::Error naming `dir` (another run holds it).
  explicit DirectoryLock(const Directory& dir);
  explicit DirectoryLock(const std::string& dir);
  ~DirectoryLock();
  DirectoryLock(DirectoryLock&& o) noexcept;
  DirectoryLock& operator=(DirectoryLock&& o) noexcept;
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace emc::output
