#pragma once
// Field output: HDF5 files with an XDMF index that ParaView opens as a time series. Rank 0
// writes arrays already gathered in global node / element order.
#include <string>
#include <utility>
#include <vector>

#include "emcontact/output/open_directory.hpp"

namespace emc::output {

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
  /// file is written, listed and removed relative to `dir`.
  FieldWriter(Directory dir, const std::vector<double>& X, const std::vector<long long>& tets,
              const std::vector<int>& body_of_tet);
  /// The same in the directory named `dir` (created if missing).
  FieldWriter(const std::string& dir, const std::vector<double>& X,
              const std::vector<long long>& tets, const std::vector<int>& body_of_tet);
  /// Writes DIR/fields_<step>.h5 atomically, then rewrites DIR/fields.xdmf atomically.
  void write(const FieldFrame& f);
  /// After a restart from `step`: lists the frames of DIR at steps <= `step` (their files
  /// readable), removes the frame files after it (the earlier run's), rewrites fields.xdmf.
  void resume(long step);

 private:
  Directory dir_;
  long long num_nodes_ = 0, num_tets_ = 0;
  std::vector<std::pair<long, double>> frames_;  // (step, time)
  void write_xdmf() const;
};

}  // namespace emc::output
