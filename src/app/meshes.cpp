#include "emcontact/app/meshes.hpp"

#include <Teuchos_CommHelpers.hpp>

#include "emcontact/error.hpp"
#include "emcontact/mesh/generate.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {

namespace {

void bcast_string(const Comm& comm, std::string& s) {
  std::vector<char> v(s.begin(), s.end());
  broadcast_vector(comm, v);
  s.assign(v.begin(), v.end());
}

void bcast_mesh(const Comm& comm, mesh::BodyMesh& m) {
  broadcast_vector(comm, m.X);
  broadcast_vector(comm, m.tets);
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

}  // namespace

std::vector<mesh::BodyMesh> build_meshes(const Teuchos::ParameterList& params,
                                         const std::string& input_dir, const std::string& file,
                                         const Comm& comm) {
  const auto& bodies = params.sublist("Bodies");
  std::vector<mesh::BodyMesh> meshes;
  std::string error;
  if (comm.getRank() == 0) {
    try {
      for (auto it = bodies.begin(); it != bodies.end(); ++it) {
        const std::string name = bodies.name(it);
        if (!bodies.isSublist(name)) continue;
        const std::string where = file + ": Bodies/" + name + "/Mesh";
        meshes.push_back(mesh::build_mesh(bodies.sublist(name).sublist("Mesh"), input_dir, where));
        mesh::check_tets(meshes.back(), where);
      }
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "mesh generation failed";
    }
  }
  bcast_string(comm, error);
  if (!error.empty()) throw InputError(error);
  long long nb = static_cast<long long>(meshes.size());
  Teuchos::broadcast(comm, 0, 1, &nb);
  meshes.resize(nb);
  for (auto& m : meshes) bcast_mesh(comm, m);
  return meshes;
}

}  // namespace emc::app
