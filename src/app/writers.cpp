// A run's output writers (see writers.hpp).
#include "emcontact/app/writers.hpp"

#include <Teuchos_TimeMonitor.hpp>
#include <cmath>

#include "emcontact/output/parallel_hdf5.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {

namespace {

/// The field writer of every rank, each with its block of rows of mesh.h5 and the frames
/// (collective; writes mesh.h5).
void make_field_writer(const fem::Discretization& disc, const OutputDirectory& dir, Writers& w) {
  const auto& model = disc.model();
  const auto layout =
      output::FieldLayout::blocks(raw_comm(*disc.comm()), model.num_nodes(), model.global_tets);
  w.node_rows = std::make_unique<RootGather>(disc.owned_map(), fem::dof_gid(layout.node_first, 0),
                                             3 * layout.node_count);
  w.tet_rows = std::make_unique<RootGather>(disc.element_map(), layout.tet_first, layout.tet_count);
  // this rank's rows: the nodes' coordinates and the tets (4 nodes and the body of each), from
  // the ranks that own them
  const std::vector<double> X = (*w.node_rows)(*disc.reference_positions());
  std::vector<long long> tets(4 * static_cast<std::size_t>(layout.tet_count));
  std::vector<int> body(static_cast<std::size_t>(layout.tet_count));
  const auto& mine = disc.part().my_tets;
  for (int c = 0; c < 5; ++c) {
    Vector v(disc.element_map());
    {
      auto h = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t k = 0; k < mine.size(); ++k)
        h(k, 0) = c < 4 ? model.tets[4 * std::size_t(mine[k]) + c] : model.body_of_tet[mine[k]];
    }
    const auto rows = (*w.tet_rows)(v);
    for (std::size_t j = 0; j < rows.size(); ++j)
      if (c < 4)
        tets[4 * j + c] = std::llround(rows[j]);
      else
        body[j] = static_cast<int>(rows[j]);
  }
  w.fields = std::make_unique<output::FieldWriter>(output::shared_directory(layout.comm, dir.dir()),
                                                   layout, X, tets, body);
}

}  // namespace

void Writers::fields_frame(const fem::Discretization& disc, const time::State& s) {
  if (every <= 0 || s.step % every != 0) return;
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
  output::FieldFrame f;
  f.step = s.step;
  f.time = s.t;
  f.displacement = (*node_rows)(*s.u);
  f.velocity = (*node_rows)(*s.V);
  f.von_mises = (*tet_rows)(*disc.von_mises(*s.u));
  // per node contact status and normal force, packed in the x and y dofs of a dof vector
  Vector c(disc.owned_map());
  {
    auto h = c.getLocalViewHost(Tpetra::Access::OverwriteAll);
    Kokkos::deep_copy(h, 0.0);
    // the nodes the monitors count (§6.5): 1 active, 2 released at the end of the step
    for (std::size_t k = 0; k < s.contact_nodes.size(); ++k) {
      const LO l = disc.owned_map()->getLocalElement(fem::dof_gid(s.contact_nodes[k], 0));
      h(l, 0) = s.contact_status[k];
      h(l + 1, 0) = s.contact_force[k];
      h(l + 2, 0) = k < s.contact_slip.size() ? s.contact_slip[k] : 0;
    }
  }
  const auto packed = (*node_rows)(c);
  for (std::size_t n = 0; 3 * n < packed.size(); ++n) {
    f.contact_status.push_back(packed[3 * n]);
    f.normal_force.push_back(packed[3 * n + 1]);
    f.slip.push_back(packed[3 * n + 2]);
  }
  fields->write(f);
}

Writers make_writers(const fem::Discretization& disc, const OutputDirectory& dir, int every,
                     std::unique_ptr<RootGather> dofs) {
  Writers w;
  w.every = every;
  on_root(*disc.comm(), [&] {  // a refusal stops every rank
    w.monitors = std::make_unique<output::MonitorWriter>(dir.dir(), "monitors.csv");
  });
  w.dofs = std::move(dofs);
  if (every > 0) make_field_writer(disc, dir, w);
  return w;
}

}  // namespace emc::app
