#pragma once
// HDF5 files written whole: built in memory (the core driver, no backing store), then written
// with atomic_write. HDF5 itself never opens a name in the output directory, so a planted link
// cannot redirect it, and a failed write (disk full) keeps the previous file.
#include <hdf5.h>

#include <functional>
#include <string>

namespace emc::output {

/// Builds an HDF5 file in memory with `fill(file)` (which throws on error), then replaces
/// `path` with it atomically. Throws emc::Error naming `path`; `path` is then unchanged.
void write_hdf5_file(const std::string& path, const std::function<void(hid_t)>& fill);

/// Stops HDF5 printing its error stack: every failure is reported as one emc::Error line.
void silence_hdf5_errors();

}  // namespace emc::output
