#pragma once
// Checkpoint files: the complete state of a run at the end of a step (displacements,
// velocities, the predictor's last increment, the active contact set with its projection data,
// normal forces and Coulomb states, step size and counters) in HDF5, written atomically: by
// one rank whole, or by every rank together, each its block of the per-node arrays.
#include <mpi.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

/// Values per active entry in Checkpoint::active (slave, pair, facet, xi, eta) and in
/// Checkpoint::state (slip, direction, off): contact::kPackedActive and contact::kPackedState.
constexpr std::size_t kActiveValues = 5, kStateValues = 5;

struct Checkpoint {
  long step = 0;
  double t = 0, dt = 0, last_h = 0;
  int good_steps = 0, last_iterations = 0;
  double newton_contraction = 0;  ///< absent from older checkpoints (then 0)
  double nominal_dt = 0;          ///< the input's Time/dt of the run that wrote it
  std::string model;  ///< the fingerprint of the model it belongs to (one "key: value" a line)
  std::vector<double> u, V;            ///< 3 per node, global order
  std::vector<double> last_increment;  ///< 3 per node, or empty (no step taken yet)
  std::vector<double> active;          ///< 5 per active slave: slave, pair, facet, xi, eta
  std::vector<double> normal_force;    ///< f_N per active slave
  /// 5 per active slave: slip (1) or stick (0), the direction of its last slip, off (1: a
  /// Coulomb entry that last slid off its facet, then stuck) (docs/THEORY.md §11.4, §11.7);
  /// empty in checkpoints written before it (then every entry sticks, and none is off)
  std::vector<double> state;

  /// The scalars as stored (step, t, dt, last_h, good_steps, last_iterations,
  /// newton_contraction, nominal_dt), and back (6 to 8 values, the counters whole numbers
  /// >= 0; throws emc::Error naming `path` otherwise).
  std::vector<double> scalars() const;
  void set_scalars(const std::vector<double>& s, const std::string& path);
};

/// What the model that reads a checkpoint needs of it: checked before any dataset is read.
struct CheckpointShape {
  std::size_t values = 0;       ///< of u and V (and last_increment, or none): 3 per node
  std::size_t max_entries = 0;  ///< active entries at most (the slave nodes of its pairs)
  /// Called with the stored model fingerprint before any dataset is read; throws to refuse it.
  std::function<void(const std::string& model)> check_model;
};

/// Writes the file `name` of `dir` atomically (temporary name, then rename); throws emc::Error
/// naming it.
void write_checkpoint(const Directory& dir, const std::string& name, const Checkpoint& c);
void write_checkpoint(const std::string& path, const Checkpoint& c);
/// Collective over `comm`: writes `name` of `dir` (every rank's output::shared_directory) as
/// write_checkpoint writes the whole, the same bytes and checksum, with parallel HDF5: `mine`
/// holds this rank's block (output::block_of(values, rank, ranks)) of u, V and last_increment
/// (empty on every rank: none), rank 0's the other parts (the others' are ignored). Nothing is
/// gathered: the checksum is summed along the ranks. One rank: write_checkpoint. Throws
/// emc::Error on every rank if any failed; the previous file is then unchanged.
void write_checkpoint_collectively(MPI_Comm comm, const Directory& dir, const std::string& name,
                                   const Checkpoint& mine, unsigned long long values);
/// Collective over `comm`: read_checkpoint(path, shape), each rank reading only its block
/// (output::block_of(shape.values, rank, ranks)) of u, V and last_increment and the other
/// parts whole; the checksum summed along the ranks. Any rank's refusal (a rank that cannot
/// read its part among them) is thrown on every rank, the lowest rank's message.
Checkpoint read_checkpoint_collectively(MPI_Comm comm, const std::string& path,
                                        const CheckpointShape& shape);
/// Reads a checkpoint; throws emc::Error naming the file and what is wrong: not a regular
/// file, not a checkpoint, written before checkpoints had a model fingerprint and checksum, a
/// dataset or attribute of another type, rank or length than written (checked before it is
/// read), a model `shape.check_model` refuses, or a checksum that does not match its contents.
Checkpoint read_checkpoint(const std::string& path, const CheckpointShape& shape);
/// The same without a model: the lengths are only checked against each other.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace emc::output
