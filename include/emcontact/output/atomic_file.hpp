#pragma once
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
}  // namespace emc::output
