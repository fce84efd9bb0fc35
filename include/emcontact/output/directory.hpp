#pragma once
// The output directory's own files: which of them a directory holds, removing exactly those
// (--overwrite), and the lock that keeps two runs out of one directory.
#include <string>
#include <vector>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// "fields_00000042.h5": the frame file of `step` (>= 0), relative to the output directory.
std::string frame_file_name(long step);

/// The step of a file named exactly as frame_file_name(step) makes it, or -1 for any other name
/// (fields_0.h5, fields_0000001.h5 or a 20-digit step are not frame files).
long frame_step(const std::string& name);

/// The names in `dir` of files an emcontact run writes there: monitors.csv, checkpoint.h5,
/// fields.xdmf, fields_<step>.h5, mesh.h5, energies.png (sorted).
std::vector<std::string> owned_files(const Directory& dir);
std::vector<std::string> owned_files(const std::string& dir);

/// The bytes of the owned files of `dir` (what --overwrite frees).
double owned_bytes(const Directory& dir);

/// Removes the owned files of `dir` and the temporaries left by a killed writer (named exactly as
/// create_temp names them: `<owned>.tmp.<12 letters or digits>`, `.png` after energies.png's);
/// never any other file, never a directory. Throws emc::Error naming a file it cannot remove.
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
