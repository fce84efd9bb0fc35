#pragma once
#include <string>

namespace emc::output {
/// Writes `content` to `path` atomically: a temporary file in the same directory, fsync, then
/// rename, so a killed run leaves either the old or the new complete file.
void atomic_write(const std::string& path, const std::string& content);
/// The directory part of `path` ("." if it has none, "/" for a file in the root).
std::string parent_directory(const std::string& path);
/// Creates the directory (and parents) or throws emc::Error naming it.
void make_directory(const std::string& dir);
}  // namespace emc::output
