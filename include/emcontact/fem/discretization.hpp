#pragma once
// The distributed discretization: element partition, Tpetra maps of owned and owned+shared
// dofs, the FE graph (built once), per-element geometry in Kokkos views, and the assembly
// driver that launches the element kernels and scatters into a Tpetra::FECrsMatrix.
#include <Teuchos_RCP.hpp>
#include <map>
#include <vector>

#include "emcontact/fem/model.hpp"
#include "emcontact/fem/partition.hpp"
#include "emcontact/types.hpp"
#include "kernels/tet4_elements.hpp"

namespace emc::fem {

/// Dof numbering: global dof 3 n + c of node n, component c.
inline GO dof_gid(long long node, int c) {
  return 3 * node + c;
}

/// My elements of one kernel material type (kernels::Lame: svk; kernels::LogHyperelastic:
/// neo-hookean and mooney-rivlin) in the kernel library's record (kernels/tet4_elements.hpp):
/// their nodes' indices in the overlap map (dof 3 k + c of node k), geometry, material, density
/// and massless nodes, and what their loops need.
template <class Material>
struct ElementGroup {
  kernels::TetElements<MemSpace, Material> tets;
  std::vector<int> local;  ///< each tet's index among my elements (element_map's order)
  Kokkos::View<int*, MemSpace> local_view;                         ///< the same on the device
  Kokkos::View<int* [12], Kokkos::LayoutRight, MemSpace> columns;  ///< dofs' graph columns
  kernels::TetColouring<MemSpace> colouring;
  mutable kernels::TetOffsets<MemSpace> offsets;  ///< element entries in the values
  int size() const { return static_cast<int>(local.size()); }
};
using Elements = kernels::TetElements<MemSpace>;

struct AssemblyInfo {
  double min_detF = 1;       ///< smallest det F_{n+1} over all elements (global)
  long long worst_tet = -1;  ///< global id (0-based) of the element with that det F
};

class Discretization {
 public:
  /// On a model every rank holds whole (tests): partition() of it.
  Discretization(const Model& model, Teuchos::RCP<const Comm> comm);
  /// On a distributed model and its part (fem::distribute).
  Discretization(const Model& model, Partition part, Teuchos::RCP<const Comm> comm);

  const Model& model() const { return model_; }
  const Partition& part() const { return part_; }
  Teuchos::RCP<const Comm> comm() const { return comm_; }
  Teuchos::RCP<const Map> owned_map() const { return owned_; }       ///< owned dofs
  Teuchos::RCP<const Map> overlap_map() const { return overlap_; }   ///< owned + shared dofs
  Teuchos::RCP<const Map> element_map() const { return elements_; }  ///< my tets
  Teuchos::RCP<FEGraph> graph() const { return graph_; }
  /// My Saint-Venant-Kirchhoff elements' chunks by colour (the loops of
  /// Solver/Assembly/scatter = coloured).
  const kernels::TetColouring<MemSpace>& colouring() const { return svk_.colouring; }
  /// My Saint-Venant-Kirchhoff elements (their nodes: overlap-map node indices).
  const Elements& tets() const { return svk_.tets; }

  /// The reference coordinates of the owned nodes: coordinate c of node n at dof 3 n + c.
  Teuchos::RCP<Vector> reference_positions() const;

  /// Copies owned values to an owned+shared vector.
  void to_overlap(const Vector& owned, Vector& overlap) const;
  Teuchos::RCP<Vector> new_overlap_vector() const;

  /// Residual of eq. 20 into r, the Newton matrix (2/dt^2) M + K into A (if not null), and
  /// the round-off scale of r (docs/THEORY.md §1.6, Newton's round-off floor) into scale (if
  /// not null).
  /// Element loops as model().scatter says: coloured, the sums of every entry are in the same
  /// order whatever the number of threads (bitwise reproducible).
  /// u0, V0 = state at t_n, u1 = current iterate; all owned vectors.
  AssemblyInfo assemble(const Vector& u0, const Vector& V0, const Vector& u1, double dt,
                        FEMatrix* A, Vector& r, Vector* scale) const;

  /// Mv = M v with the mass matrix (docs/THEORY.md §1.3; with massless nodes, §6.8); owned vectors.
  void apply_mass(const Vector& v, Vector& Mv) const;

  /// Monitored quantities of (u, V) summed over all ranks (docs/THEORY.md §1.9, eq. 23-24).
  kernels::Monitors monitors(const Vector& u, const Vector& V) const;

  /// Von Mises stress per owned element (on element_map()).
  Teuchos::RCP<Vector> von_mises(const Vector& u) const;

 private:
  const Model& model_;
  Teuchos::RCP<const Comm> comm_;
  Partition part_;
  Teuchos::RCP<const Map> owned_, overlap_, elements_;
  Teuchos::RCP<const Import> importer_;
  Teuchos::RCP<const Export> exporter_;
  Teuchos::RCP<FEGraph> graph_;
  ElementGroup<kernels::Lame> svk_;               ///< my svk elements
  ElementGroup<kernels::LogHyperelastic> hyper_;  ///< my neo-hookean and mooney-rivlin ones
  /// f(group) for each non-empty group, svk first.
  template <class F>
  void for_each_group(F&& f) const {
    if (svk_.size() > 0) f(svk_);
    if (hyper_.size() > 0) f(hyper_);
  }

  /// docs/THEORY.md §6.8: the mass of the elements with massless nodes, M' = sum_e T_e^T M_e T_e,
  /// on my owned rows (a scalar times I_3 per node pair); those elements' kernels leave it out.
  struct MovedMass {
    Teuchos::RCP<Matrix> M, absM;             ///< M' and its entries' absolute values (the scale)
    Teuchos::RCP<Vector> row_sums;            ///< M' 1 (the centre of mass)
    std::map<int, std::vector<int>> columns;  ///< per owned node row, its node columns
    Kokkos::View<int*, ExecSpace> offsets;    ///< M's entries in the Newton matrix's values
  };
  Teuchos::RCP<MovedMass> moved_;  ///< null without massless nodes

  template <class Material>
  void build_offsets(const ElementGroup<Material>& g,
                     const FEMatrix::local_matrix_device_type& lcl) const;
  /// A group's coloured loops when model().scatter says so, else null (one loop, atomic adds).
  template <class Material>
  const kernels::TetColouring<MemSpace>* loops(const ElementGroup<Material>& g) const {
    return model_.scatter == Scatter::coloured ? &g.colouring : nullptr;
  }
  void build_moved_mass();
  void add_moved_mass(const FEMatrix::local_matrix_device_type& lcl, double c) const;
  /// r += c2 M' (u1 - u0) - c1 M' V0, scale += |M'| (|c2 (u1 - u0)| + |c1 V0|) (owned vectors).
  void moved_mass_residual(const Vector& u0, const Vector& V0, const Vector& u1, double dt,
                           Vector& r, Vector* scale) const;
  /// Adds my owned rows' kinetic energy, L, J and mass moment of the moved mass to m.
  void add_moved_monitors(const Vector& u, const Vector& V, kernels::Monitors& m) const;

  void build_maps();
  void build_element_data();
  void build_graph();
  /// The group's columns (from the graph's column map) and colouring.
  template <class Material>
  void finish_group(ElementGroup<Material>& g);
};

}  // namespace emc::fem
