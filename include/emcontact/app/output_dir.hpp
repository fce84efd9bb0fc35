#pragma once
// The output directory of a run (--output or Output/directory): checked, created, locked.
#include <string>

#include "emcontact/app/run.hpp"
#include "emcontact/output/directory.hpp"
#include "emcontact/output/parameters.hpp"
#include "emcontact/types.hpp"

namespace emc::app {

/// Rank 0 creates the directory and locks it while this object lives, then applies the rule for
/// a directory holding an earlier run's files (README, "Output"): a new run refuses it unless
/// --overwrite, which removes exactly those files; a restart from a checkpoint in the directory
/// continues there; a restart into another directory (a branch) is a new run there.
/// Collective: on a refusal every rank throws emc::Error with rank 0's message.
class OutputDirectory {
 public:
  OutputDirectory(const Options& opt, const output::Settings& output, const Comm& comm);
  const std::string& path() const { return path_; }
  /// The directory of the --restart checkpoint: the monitors up to its step are read there.
  const std::string& restart_source() const { return source_; }

 private:
  std::string path_, source_;
  output::DirectoryLock lock_;  // rank 0 only
  void prepare(const Options& opt);
};

}  // namespace emc::app
