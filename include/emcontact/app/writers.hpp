#pragma once
// A run's output writers: the monitors (rank 0), the field frames and the checkpoints' blocks.
#include <memory>

#include "emcontact/app/output_dir.hpp"
#include "emcontact/app/root_gather.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/time/stepper.hpp"

namespace emc::app {

/// The monitors (rank 0), the fields (every rank its block of rows: node_rows, tet_rows) and the
/// checkpoints' blocks (dofs).
struct Writers {
  std::unique_ptr<output::MonitorWriter> monitors;
  std::unique_ptr<output::FieldWriter> fields;
  std::unique_ptr<RootGather> dofs, node_rows, tet_rows;
  int every = 0;

  /// A field frame of the state, at the steps `every` divides (collective).
  void fields_frame(const fem::Discretization& disc, const time::State& s);
};

/// The writers into `dir` and the gathers (every rank; writes mesh.h5 if `every` > 0); `dofs`
/// is built before, for the restart.
Writers make_writers(const fem::Discretization& disc, const OutputDirectory& dir, int every,
                     std::unique_ptr<RootGather> dofs);

}  // namespace emc::app
