#pragma once
// Field output: HDF5 files with an XDMF index that ParaView opens as a time series, in global
// node / element order. On several ranks every rank writes its own block of rows of each array
// (parallel HDF5, parallel_hdf5.hpp); rank 0 writes the index.
#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// The rows of the field files a rank writes: nodes [nodes.first, nodes.first + nodes.count) of
/// num_nodes and tets likewise; a frame and the mesh arrays hold those rows only.
struct FieldLayout {
  MPI_Comm comm = MPI_COMM_SELF;  ///< the ranks writing together (one rank: MPI_COMM_SELF)
  long long num_nodes = 0, num_tets = 0;
  long long node_first = 0, node_count = 0, tet_first = 0, tet_count = 0;
  /// This rank's contiguous block of `nodes` and `tets` rows among the ranks of `comm`.
  static FieldLayout blocks(MPI_Comm comm, long long nodes, long long tets);
};

/// One output frame: this rank's rows (FieldLayout) of each field.
struct FieldFrame {
  long step = 0;
  double time = 0;
  std::vector<double> displacement;    ///< 3 per node
  std::vector<double> velocity;        ///< 3 per node
  std::vector<double> von_mises;       ///< 1 per tet (Cauchy stress at t_n)
  std::vector<double> contact_status;  ///< 1 per node: 1 active slave, 0 otherwise (or empty)
  std::vector<double> normal_force;    ///< 1 per node: f_N of an active slave (or empty)
  std::vector<double> slip;            ///< 1 per node: 1 sliding (Coulomb), 0 otherwise
};

class FieldWriter {
 public:
  /// DIR/mesh.h5 (geometry X, topology tets, body id per tet) is written once here; every
  /// file is written, listed and removed relative to `dir`. One rank: the whole arrays.
  FieldWriter(Directory dir, const std::vector<double>& X, const std::vector<long long>& tets,
              const std::vector<int>& body_of_tet);
  /// Collective over layout.comm: each rank gives its rows of X, tets and body_of_tet and its
  /// own descriptor of the output directory (shared_directory); rank 0 writes the index.
  FieldWriter(Directory dir, const FieldLayout& layout, const std::vector<double>& X,
              const std::vector<long long>& tets, const std::vector<int>& body_of_tet);
  /// The same in the directory named `dir` (created if missing).
  FieldWriter(const std::string& dir, const std::vector<double>& X,
              const std::vector<long long>& tets, const std::vector<int>& body_of_tet);
  /// Writes DIR/fields_<step>.h5 atomically, then adds its grid to DIR/fields.xdmf: written
  /// over the index's closing tags, O(one frame) whatever the number of frames (collective).
  /// The index is replaced whole (atomically) at its first frame and when a step is written
  /// again; a run killed in the middle of an addition gets its index rebuilt by --restart.
  void write(const FieldFrame& f);
  /// After a restart from `step`: lists the frames of DIR at steps <= `step` (their files
  /// readable), removes the frame files after it (the earlier run's), rewrites fields.xdmf
  /// (rank 0; collective).
  void resume(long step);

 private:
  Directory dir_;
  FieldLayout layout_;
  std::vector<std::pair<long, double>> frames_;  // (step, time)
  GrowingFile xdmf_;                             // rank 0: fields.xdmf, once written whole
  void resume_root(long step);
  void write_xdmf();                         ///< rank 0: the index of frames_, whole
  void add_to_xdmf(long step, double time);  ///< rank 0: one grid over the closing tags
  std::string xdmf_grid(long step, double time) const;
};

}  // namespace emc::output
