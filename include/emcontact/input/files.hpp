#pragma once
// Files named by the user (the input, a mesh, a checkpoint) must be regular files: a FIFO
// blocks the reader forever, a directory or a device (/dev/zero) is never what was meant.
#include <string>

namespace emc::input {

/// Throws InputError "<path>: cannot read the <what>: <reason>" unless `path` is a regular
/// file this process can read (reasons: no such file, it is a directory / FIFO / device / not
/// a regular file, or the open error).
void check_regular_file(const std::string& path, const std::string& what);

}  // namespace emc::input
