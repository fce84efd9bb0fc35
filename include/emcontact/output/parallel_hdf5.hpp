#pragma once
// HDF5 files written by every rank together (parallel HDF5 over MPI-IO): each rank writes its
// own rows of every dataset (a hyperslab), nothing is gathered to one rank. The file is a
// temporary of the output directory (created by rank 0 exclusively, never through a link,
// opened by every rank through its own descriptor of that directory), renamed into place by
// rank 0 once every rank's writes are complete: a killed run leaves the previous file whole.
#include <hdf5.h>
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "emcontact/output/open_directory.hpp"
#include "emcontact/parallel.hpp"

namespace emc::output {

/// A dataset of `rows` rows of `width` values (width 0: one scalar, written by rank 0), of
/// which this rank holds rows [offset, offset + count) in `data`, row-major.
struct SlabDataset {
  std::string name;  ///< "/displacement"
  hid_t file_type;   ///< H5T_IEEE_F64LE, H5T_STD_I64LE, ...
  hid_t mem_type;    ///< H5T_NATIVE_DOUBLE, ...
  unsigned long long rows = 1, width = 0, offset = 0, count = 0;
  const void* data = nullptr;
};

/// Rank r's rows of an array of n rows cut into `ranks` contiguous blocks: [first, first + count).
struct Block {
  long long first = 0, count = 0;
};
Block block_of(long long n, int rank, int ranks);

/// Collective over `comm`: this rank's descriptor of rank 0's output directory `root_dir`
/// (ignored elsewhere): rank 0's own copy; the other ranks open the path rank 0 gives and
/// refuse (emc::Error on every rank) a directory that is not the one rank 0 holds (another
/// inode: renamed or replaced in between).
Directory shared_directory(MPI_Comm comm, const Directory& root_dir);

/// Collective over `comm`: writes `sets` (the same names, types and shapes on every rank, each
/// rank its own rows) into the file `name` of `dir` (every rank's shared_directory), replacing
/// it atomically; then `attributes` (if given) on every rank with the open file, writing the
/// same attributes everywhere (collective in parallel HDF5). Throws emc::Error naming the file
/// on every rank if any rank failed; the file is then unchanged and no temporary is left.
void write_hdf5_collectively(MPI_Comm comm, const Directory& dir, const std::string& name,
                             const std::vector<SlabDataset>& sets,
                             const std::function<void(hid_t file)>& attributes = {});

}  // namespace emc::output
