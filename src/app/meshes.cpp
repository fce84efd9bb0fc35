#include "emcontact/app/meshes.hpp"

#include <Teuchos_CommHelpers.hpp>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/mesh/generate.hpp"
#include "emcontact/os/memory.hpp"
#include "emcontact/os/mesh_process.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {

namespace {

void bcast_string(const Comm& comm, std::string& s) {
  std::vector<char> v(s.begin(), s.end());
  broadcast_vector(comm, v);
  s.assign(v.begin(), v.end());
}

/// Rank 0's mesh m to every rank, but for the tetrahedra: the others get their count and
/// boundary triangles (fem::distribute later hands each rank its part of them).
void bcast_mesh(const Comm& comm, mesh::BodyMesh& m) {
  broadcast_vector(comm, m.X);
  long long tets = m.body_tets();
  Teuchos::broadcast(comm, 0, 1, &tets);
  if (comm.getRank() == 0 && m.boundary.empty() && tets > 0)
    m.boundary = mesh::boundary_triangles(m);
  broadcast_vector(comm, m.boundary);
  if (comm.getRank() != 0 && tets > 0) m.dropped_tets = static_cast<int>(tets);
  long long ns = static_cast<long long>(m.surfaces.size());
  Teuchos::broadcast(comm, 0, 1, &ns);
  auto it = m.surfaces.begin();
  std::map<std::string, std::vector<std::array<int, 3>>> surfaces;
  for (long long k = 0; k < ns; ++k) {
    std::string name = comm.getRank() == 0 ? it->first : std::string();
    std::vector<std::array<int, 3>> tris = comm.getRank() == 0 ? it->second : decltype(tris)();
    bcast_string(comm, name);
    broadcast_vector(comm, tris);
    surfaces[name] = std::move(tris);
    if (comm.getRank() == 0) ++it;
  }
  m.surfaces = std::move(surfaces);
}

/// The number of ranks of `comm` on this machine (collective).
int ranks_on_node(const Comm& comm) {
  if (comm.getSize() == 1) return 1;
  MPI_Comm local;
  MPI_Comm_split_type(raw_comm(comm), MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int n = 1;
  MPI_Comm_size(local, &n);
  MPI_Comm_free(&local);
  return n;
}

std::string count(double n) {
  return format("%.0f", n);
}

/// Gmsh fills a volume with about this fraction of mesh::estimated_tets (0.55 on the tumbling
/// box, 0.58 on the ball; more on bodies thinner than a few elements): the memory is checked
/// before meshing with this fraction of the estimate, so that no run that fits is refused, and
/// again with the real counts once the meshes are built.
constexpr double kGmshFill = 0.5;

/// Refuses a model of `tets` tetrahedra (`what`: "about 738000 tetrahedra ...") beyond
/// mesh::kMaxTets in all, or `memory_tets` beyond the memory this rank can get.
void check_model_size(double tets, double memory_tets, const std::string& what, const Comm& comm,
                      int local_ranks) {
  if (tets > mesh::kMaxTets)
    throw InputError(what + ", more than the limit of " + count(mesh::kMaxTets) +
                     " tetrahedra in all the bodies together; allowed: a coarser mesh (a "
                     "larger Mesh/size)");
  os::check_memory(memory_tets, comm.getSize(), local_ranks, what);
}

/// "file: Bodies: the meshes would hold about N tetrahedra (Bodies/a: n_a, ...)".
std::string model_text(const std::string& file, const std::string& verb, double total,
                       const std::string& per_body) {
  return file + ": Bodies: the meshes " + verb + " " + count(total) + " tetrahedra in all (" +
         per_body + ")";
}

/// Rank 0: every body's mesh, after checking that their estimated size (generated volumes)
/// and then their real size (files too) fit the limit and the memory.
std::vector<mesh::BodyMesh> build_on_root(const Teuchos::ParameterList& bodies,
                                          const std::string& input_dir, const std::string& file,
                                          const Comm& comm, int local_ranks) {
  const auto where = [&](const std::string& name) {
    return file + ": Bodies/" + input::echo(name) + "/Mesh";
  };
  double estimate = 0.0;
  std::string per_body;
  for (const std::string& name : input::sublist_names(bodies)) {
    const double n = mesh::estimated_tets(bodies.sublist(name).sublist("Mesh"), where(name));
    estimate += n;
    if (n > 0) per_body += (per_body.empty() ? "" : ", ") + input::echo(name) + ": " + count(n);
  }
  check_model_size(estimate, kGmshFill * estimate,
                   model_text(file, "would hold about", estimate, per_body), comm, local_ranks);
  std::vector<mesh::BodyMesh> meshes;
  double tets = 0.0;
  per_body.clear();
  for (const std::string& name : input::sublist_names(bodies)) {
    meshes.push_back(
        mesh::build_mesh(bodies.sublist(name).sublist("Mesh"), input_dir, where(name)));
    mesh::check_tets(meshes.back(), where(name));
    tets += meshes.back().num_tets();
    per_body += (per_body.empty() ? "" : ", ") + input::echo(name) + ": " +
                std::to_string(meshes.back().num_tets());
    check_model_size(tets, tets, model_text(file, "hold", tets, per_body), comm, local_ranks);
  }
  return meshes;
}

}  // namespace

std::vector<mesh::BodyMesh> build_meshes(const Teuchos::ParameterList& params,
                                         const std::string& input_dir, const std::string& file,
                                         const Comm& comm) {
  const auto& bodies = params.sublist("Bodies");
  const int local_ranks = ranks_on_node(comm);
  std::vector<mesh::BodyMesh> meshes;
  std::string error;
  if (comm.getRank() == 0) {
    try {
      // in a child process: Gmsh's peak memory is not rank 0's
      meshes = os::build_in_child_process(
          [&] { return build_on_root(bodies, input_dir, file, comm, local_ranks); });
    } catch (const std::exception& e) {
      error = os::is_out_of_memory(e) ? os::out_of_memory_message(e) : e.what();
      if (error.empty()) error = "mesh generation failed";
    }
  }
  bcast_string(comm, error);
  if (!error.empty()) throw InputError(error);
  long long nb = static_cast<long long>(meshes.size());
  Teuchos::broadcast(comm, 0, 1, &nb);
  meshes.resize(nb);
  long long tets = 0, nodes = 0;
  for (auto& m : meshes) {
    bcast_mesh(comm, m);
    tets += m.body_tets();
    nodes += m.num_nodes();
  }
  os::note_model_size(tets, nodes, comm.getSize(), local_ranks);
  return meshes;
}

}  // namespace emc::app
