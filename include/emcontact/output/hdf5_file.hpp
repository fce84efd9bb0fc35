#pragma once
// HDF5 files written whole: built in memory (the core driver, no backing store), then written
// with atomic_write relative to the open output directory. HDF5 itself never opens a name in
// the output directory (it reads a file there through a descriptor opened without following
// links), so neither a planted link nor a renamed directory redirects it, and a failed write
// (disk full) keeps the previous file.
#include <hdf5.h>

#include <functional>
#include <string>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// Builds an HDF5 file in memory with `fill(file)` (which throws on error), then replaces the
/// file `name` of `dir` with it atomically. Throws emc::Error naming it; it is then unchanged.
void write_hdf5_file(const Directory& dir, const std::string& name,
                     const std::function<void(hid_t)>& fill);
/// The same for `path`, its directory opened by name first.
void write_hdf5_file(const std::string& path, const std::function<void(hid_t)>& fill);

/// Opens the HDF5 file `name` of `dir` read-only, never through a link and only if it is a
/// regular file; returns a file id (close it with H5Fclose) or -1.
hid_t open_hdf5_file(const Directory& dir, const std::string& name);

/// Stops HDF5 printing its error stack: every failure is reported as one emc::Error line.
void silence_hdf5_errors();

}  // namespace emc::output
