// HDF5 files written by every rank together (see parallel_hdf5.hpp).
#include "emcontact/output/parallel_hdf5.hpp"

#include <sys/stat.h>

#include <climits>
#include <utility>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/safe_temp.hpp"
#include "hdf5_util.hpp"

namespace emc::output {
namespace {

using detail::Handle;
using detail::hdf5_error_text;

/// The memory dataspace of this rank's rows of `d` (a scalar's, or one row when it has none).
hid_t memory_space(const SlabDataset& d) {
  if (d.width == 0) return H5Screate(H5S_SCALAR);
  const hsize_t count[2] = {d.count > 0 ? d.count : 1, d.width};
  return H5Screate_simple(d.width == 1 ? 1 : 2, count, nullptr);
}

/// Selects this rank's rows of `d` in the file and memory dataspaces (none: a scalar off rank 0,
/// or a rank without rows).
bool select_rows(const SlabDataset& d, int rank, hid_t file_space, hid_t mem_space) {
  if (d.width == 0 ? rank != 0 : d.count == 0)
    return H5Sselect_none(mem_space) >= 0 && H5Sselect_none(file_space) >= 0;
  if (d.width == 0) return true;
  const hsize_t start[2] = {d.offset, 0}, count[2] = {d.count, d.width};
  return H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr) >= 0;
}

/// Creates dataset `d` in `file` and writes this rank's rows (collective); on failure the
/// reason in `error`.
bool write_slab(hid_t file, hid_t dxpl, const SlabDataset& d, int rank, std::string& error) {
  const hsize_t dims[2] = {d.rows, d.width};
  Handle space(
      d.width == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(d.width == 1 ? 1 : 2, dims, nullptr),
      H5Sclose);
  Handle set(space.valid() ? H5Dcreate2(file, d.name.c_str(), d.file_type, space.get(), H5P_DEFAULT,
                                        H5P_DEFAULT, H5P_DEFAULT)
                           : H5I_INVALID_HID,
             H5Dclose);
  Handle mem(memory_space(d), H5Sclose);
  if (!set.valid() || !mem.valid() || !select_rows(d, rank, space.get(), mem.get())) {
    error = "creating dataset " + d.name + ": " + hdf5_error_text();
    return false;
  }
  static const double none = 0;  // HDF5 refuses a null buffer even with nothing selected
  const void* data = d.data != nullptr ? d.data : &none;
  // an empty dataset has no storage to write (MPI-IO fails on it): created, not written
  if ((d.width == 0 || d.rows > 0) &&
      H5Dwrite(set.get(), d.mem_type, mem.get(), space.get(), dxpl, data) < 0) {
    error = "writing dataset " + d.name + ": " + hdf5_error_text();
    return false;
  }
  if (!set.reset()) {
    error = "closing dataset " + d.name + ": " + hdf5_error_text();
    return false;
  }
  return true;
}

/// Every rank writes its rows of `sets` into the existing (empty) file `via` (collective; the
/// ranks leave together at the first step that failed on any of them).
bool write_sets(MPI_Comm comm, const std::string& via, const std::vector<SlabDataset>& sets,
                const std::function<void(hid_t)>& attributes, std::string& error) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  const bool lists = fapl.valid() && dxpl.valid() &&
                     H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL) >= 0 &&
                     H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE) >= 0;
  if (!all_ok(comm, lists)) {
    error = "HDF5 cannot select MPI-IO: " + hdf5_error_text();
    return false;
  }
  Handle file(H5Fcreate(via.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!file.valid()) error = "HDF5 cannot open the temporary file: " + hdf5_error_text();
  if (!all_ok(comm, file.valid())) return false;
  const int rank = rank_of(comm);
  for (const SlabDataset& d : sets)
    if (!all_ok(comm, write_slab(file.get(), dxpl.get(), d, rank, error))) return false;
  bool written = true;
  if (attributes) try {
      attributes(file.get());
    } catch (const std::exception& e) {
      error = e.what();
      written = false;
    }
  if (!all_ok(comm, written)) return false;
  const bool closed = file.reset();  // flushes every rank's writes
  if (!closed) error = "HDF5 cannot close the file: " + hdf5_error_text();
  return all_ok(comm, closed);
}

}  // namespace

Block block_of(long long n, int rank, int ranks) {
  const long long first = n * rank / ranks, end = n * (rank + 1) / ranks;
  return {first, end - first};
}

Directory shared_directory(MPI_Comm comm, const Directory& root_dir) {
  const bool root = rank_of(comm) == 0;
  struct stat st {};
  unsigned long long ino = 0;
  if (root && ::fstat(root_dir.fd(), &st) == 0) ino = st.st_ino;
  MPI_Bcast(&ino, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  const std::string path = broadcast(comm, root ? root_dir.path() : std::string());
  if (root) {  // the others' verdict
    const std::string error = first_error(comm, "");
    if (!error.empty()) throw Error(error);
    return root_dir;
  }
  Directory dir;
  std::string error;
  try {
    dir = Directory(path, true);
    // the inode only: the device number of one shared file system differs between machines
    if (::fstat(dir.fd(), &st) != 0 || st.st_ino != ino)
      error = "output directory '" + path + "' is no longer the directory the run opened";
  } catch (const std::exception& e) {
    error = e.what();
  }
  error = first_error(comm, error);
  if (!error.empty()) throw Error(error);
  return dir;
}

void write_hdf5_collectively(MPI_Comm comm, const Directory& dir, const std::string& name,
                             const std::vector<SlabDataset>& sets,
                             const std::function<void(hid_t file)>& attributes) {
  const bool root = rank_of(comm) == 0;
  const std::string path = dir.path(name);
  TempFile tmp;
  std::string error;
  if (root) {
    try {
      tmp = create_temp(dir, name);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = first_error(comm, error);
  if (!error.empty()) throw Error(error);
  // every rank opens the temporary through its own descriptor of the directory: a renamed
  // directory or a link planted at its name redirects nothing
  const std::string via = "/proc/self/fd/" + std::to_string(dir.fd()) + "/" +
                          broadcast(comm, root ? tmp.name : std::string());
  const bool written = write_sets(comm, via, sets, attributes, error);
  if (root) {
    try {
      if (written) {
        commit_temp(dir, tmp, name);  // fsync, rename into place
      } else {
        discard_temp(dir, tmp);
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!written && !error.empty()) error = "cannot write '" + path + "': " + error;
  error = first_error(comm, error);
  if (error.empty() && !written) error = "cannot write '" + path + "'";
  if (!error.empty()) throw Error(error);
}

}  // namespace emc::output
