// The output directory of a run: the non-empty-directory rule and the lock (output_dir.hpp).
#include "emcontact/app/output_dir.hpp"

#include <fcntl.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {
namespace {

/// Whether `a` names the directory held by `dir`.
bool same_directory(const std::string& a, const output::Directory& dir) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::fstat(dir.fd(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

/// "a, b, c and 4 more".
std::string short_list(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 3; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 3) s += " and " + std::to_string(names.size() - 3) + " more";
  return s;
}

/// Whether `dir` has an entry `name` (a link counts, not followed).
bool has_entry(const output::Directory& dir, const char* name) {
  struct stat st {};
  return ::fstatat(dir.fd(), name, &st, AT_SYMLINK_NOFOLLOW) == 0;
}

/// Whether anything (a link too) is at `path`; throws naming it if that cannot be known.
bool exists(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) return true;
  if (errno == ENOENT) return false;
  throw Error("cannot create directory '" + path + "': " + std::strerror(errno));
}

}  // namespace

OutputDirectory::OutputDirectory(const Options& opt, const output::Settings& output,
                                 const Comm& comm, const output::OutputSize& need)
    : need_(need), every_(output.every) {
  if (!opt.restart.empty()) source_ = output::parent_directory(opt.restart);
  // a restart continues in its checkpoint's directory unless --output names another
  path_ = !opt.output_dir.empty() ? opt.output_dir : !source_.empty() ? source_ : output.directory;
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
  bool locked = false;
  if (exists(path_)) {  // a refusal comes before anything is created in it
    dir_ = output::Directory(path_);
    if (has_entry(dir_, ".emcontact.lock")) {
      lock_ = output::DirectoryLock(dir_);
      locked = true;
    }
    earlier_files_go(opt);
    check_room(opt, true);
  } else {
    check_room(opt, false);
    output::make_directory(path_);
    dir_ = output::Directory(path_);
  }
  if (!locked) lock_ = output::DirectoryLock(dir_);
  if (earlier_files_go(opt)) output::remove_owned_files(dir_);  // the rule under the lock
}

void OutputDirectory::check_room(const Options& opt, bool exists) const {
  double free = output::free_bytes(path_);
  // --overwrite frees the earlier run's files; a restart in place rewrites its own
  if (exists && free >= 0 && (opt.overwrite || !opt.restart.empty()))
    free += output::owned_bytes(dir_);
  output::check_room(path_, need_, free, every_);
}

bool OutputDirectory::earlier_files_go(const Options& opt) const {
  if (!opt.restart.empty() && same_directory(source_, dir_)) {
    if (opt.overwrite)
      throw Error("--overwrite with --restart " + opt.restart + ": the restart continues in '" +
                  path_ + "' and needs its files; drop --overwrite or choose another --output");
    return false;  // continues the run of this directory
  }
  const auto owned = output::owned_files(dir_);
  if (owned.empty()) return false;
  if (!opt.overwrite)
    throw Error("output directory '" + path_ + "' holds the files of an earlier run (" +
                short_list(owned) +
                "); add --overwrite to replace them, --restart DIR/checkpoint.h5 to continue "
                "that run, or choose another --output");
  return true;
}

}  // namespace emc::app
