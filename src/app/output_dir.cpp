// The output directory of a run: the non-empty-directory rule and the lock (output_dir.hpp).
#include "emcontact/app/output_dir.hpp"

#include <sys/stat.h>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {
namespace {

/// Whether `a` and `b` name the same existing directory.
bool same_directory(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

/// "a, b, c and 4 more".
std::string short_list(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 3; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 3) s += " and " + std::to_string(names.size() - 3) + " more";
  return s;
}

}  // namespace

OutputDirectory::OutputDirectory(const Options& opt, const output::Settings& output,
                                 const Comm& comm) {
  path_ = opt.output_dir.empty() ? output.directory : opt.output_dir;
  if (!opt.restart.empty()) source_ = output::parent_directory(opt.restart);
  if (path_.empty())
    throw InputError(opt.input +
                     ": parameter 'Output/directory': empty; allowed: a directory name "
                     "(or --output DIR)");
  std::string error;
  if (comm.getRank() == 0) {
    try {
      prepare(opt);
    } catch (const Error& e) {
      error = e.what();
    }
  }
  std::vector<char> msg(error.begin(), error.end());
  broadcast_vector(comm, msg);  // every rank stops, with rank 0's message
  if (!msg.empty()) throw Error(std::string(msg.begin(), msg.end()));
}

void OutputDirectory::prepare(const Options& opt) {
  output::make_directory(path_);
  lock_ = output::DirectoryLock(path_);
  if (!opt.restart.empty() && same_directory(source_, path_)) {
    if (opt.overwrite)
      throw Error("--overwrite with --restart " + opt.restart + ": the restart continues in '" +
                  path_ + "' and needs its files; drop --overwrite or choose another --output");
    return;  // continues the run of this directory
  }
  const auto owned = output::owned_files(path_);
  if (owned.empty()) return;
  if (!opt.overwrite)
    throw Error("output directory '" + path_ + "' holds the files of an earlier run (" +
                short_list(owned) +
                "); add --overwrite to replace them, --restart DIR/checkpoint.h5 to continue "
                "that run, or choose another --output");
  output::remove_owned_files(path_);
}

}  // namespace emc::app
