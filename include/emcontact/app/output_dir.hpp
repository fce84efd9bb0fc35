#pragma once
// The output directory of a run (--output, else the directory of the --restart checkpoint, else
// Output/directory): checked, created, held open, locked.
#include <string>

#include "emcontact/app/run.hpp"
#include "emcontact/output/directory.hpp"
#include "emcontact/output/open_directory.hpp"
#include "emcontact/output/parameters.hpp"
#include "emcontact/output/space.hpp"
#include "emcontact/types.hpp"

namespace emc::app {

/// Rank 0 applies the rule for a directory holding an earlier run's files (docs/user-guide.md):
/// a new run refuses it unless --overwrite, which removes exactly those files; a restart from a
/// checkpoint in the directory continues there; a restart into another directory (a branch) is
/// a new run there. A refusal comes before anything is created (when the directory exists,
/// under its lock if it has a lock file). Then it creates the directory, opens it once and
/// locks it while this object lives, and applies the rule again under the lock. Every file of
/// the run is written relative to dir(). Collective: on a refusal every rank throws emc::Error
/// with rank 0's message. Before anything is created or removed, the output's estimated size
/// `need` is checked against the room on the directory's file system (output::check_room).
class OutputDirectory {
 public:
  OutputDirectory(const Options& opt, const output::Settings& output, const Comm& comm,
                  const output::OutputSize& need = {});
  /// The name it was given (for messages).
  const std::string& path() const { return path_; }
  /// The directory held open (rank 0; not open on the other ranks).
  const output::Directory& dir() const { return dir_; }

 private:
  std::string path_, source_;
  output::Directory dir_;       // rank 0 only
  output::DirectoryLock lock_;  // rank 0 only
  output::OutputSize need_;
  int every_ = 0;
  void prepare(const Options& opt);
  void check_room(const Options& opt, bool exists) const;
  bool earlier_files_go(const Options& opt) const;
};

}  // namespace emc::app
