// The Gmsh session guard and the conversion of tets (from Gmsh, or with a node table) into a
// BodyMesh.
#include <gmsh.h>

#include <algorithm>

#include "emcontact/error.hpp"
#include "internal.hpp"

namespace emc::mesh::detail {
namespace {

int g_session_depth = 0;  ///< number of live GmshSession guards (Gmsh is a process singleton)

/// Quiet, single-threaded, reproducible Gmsh: the same input gives the same mesh.
void set_session_options() {
  gmsh::option::setNumber("General.Terminal", 0);   // nothing on the console
  gmsh::option::setNumber("General.Verbosity", 2);  // log errors and warnings only
  gmsh::option::setNumber("General.NumThreads", 1);
  gmsh::option::setNumber("Mesh.MaxNumThreads1D", 1);
  gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
  gmsh::option::setNumber("Mesh.MaxNumThreads3D", 1);
  gmsh::option::setNumber("Geometry.OCCParallel", 0);
  gmsh::option::setNumber("Mesh.RandomSeed", 1);
  gmsh::option::setNumber("Mesh.Algorithm", 6);    // Frontal-Delaunay surfaces
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay volumes
  gmsh::logger::start();                           // keep messages for last_error()
}

}  // namespace

GmshSession::GmshSession() {
  if (g_session_depth++ > 0) return;
  try {
    gmsh::initialize(0, nullptr, false);  // no argv, no user configuration files
    set_session_options();
  } catch (...) {
    g_session_depth = 0;
    try {
      gmsh::finalize();
    } catch (...) {
      // Keep the initialization error, not this one.
    }
    rethrow_gmsh_error("Gmsh", "initialization failed");
  }
}

GmshSession::~GmshSession() {
  if (--g_session_depth > 0) return;
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
    // A destructor must not throw; Gmsh is unusable anyway if finalize fails.
  }
}

std::string GmshSession::last_error() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
    error.clear();
  }
  return error;
}

void rethrow_gmsh_error(const std::string& where, const std::string& what) {
  std::string message;
  try {
    throw;
  } catch (const InputError&) {
    throw;                          // already a user-facing message
  } catch (const std::string& s) {  // Gmsh 4.8 throws the error text
    message = s;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = GmshSession::last_error();
  }
  if (message.empty()) message = "unknown Gmsh error";
  throw InputError(where + ": " + what + ": " + message);
}

GmshTets gmsh_tets(const std::vector<int>& entities, const std::string& where) {
  std::vector<int> tags = entities;
  if (tags.empty()) {
    gmsh::vectorpair dim_tags;
    gmsh::model::getEntities(dim_tags, 3);
    for (const auto& dt : dim_tags) tags.push_back(dt.second);
  }
  GmshTets out;
  for (int tag : tags) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, 3, tag);
    for (int type : types) {
      if (type == 4) continue;
      std::string name;
      int dim, order, num_nodes, num_primary;
      std::vector<double> local_coords;
      gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local_coords,
                                              num_primary);
      throw InputError(where + ": volume " + std::to_string(tag) + " contains '" + name +
                       "' elements; only 4-node tetrahedra (Gmsh element type 4) are supported");
    }
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(4, element_tags, node_tags, tag);
    out.element_tags.insert(out.element_tags.end(), element_tags.begin(), element_tags.end());
    out.node_tags.insert(out.node_tags.end(), node_tags.begin(), node_tags.end());
  }
  return out;
}

int local_node(const std::vector<std::size_t>& used_tags, std::size_t tag) {
  const auto it = std::lower_bound(used_tags.begin(), used_tags.end(), tag);
  return it != used_tags.end() && *it == tag ? static_cast<int>(it - used_tags.begin()) : -1;
}

std::vector<double> node_coordinates(const std::vector<std::size_t>& element_nodes,
                                     const std::vector<std::size_t>& node_tags,
                                     const std::vector<double>& coords,
                                     std::vector<std::size_t>& used_tags) {
  used_tags = element_nodes;
  std::sort(used_tags.begin(), used_tags.end());
  used_tags.erase(std::unique(used_tags.begin(), used_tags.end()), used_tags.end());

  std::vector<double> X(3 * used_tags.size(), 0.0);
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    const int k = local_node(used_tags, node_tags[i]);
    if (k >= 0) std::copy_n(&coords[3 * i], 3, &X[3 * static_cast<std::size_t>(k)]);
  }
  return X;
}

BodyMesh body_from_tags(const GmshTets& t, const std::vector<std::size_t>& node_tags,
                        const std::vector<double>& coords, std::vector<std::size_t>& used_tags) {
  BodyMesh m;
  m.X = node_coordinates(t.node_tags, node_tags, coords, used_tags);
  m.tets.resize(t.node_tags.size());
  for (std::size_t i = 0; i < t.node_tags.size(); ++i) {
    m.tets[i] = local_node(used_tags, t.node_tags[i]);
  }
  return m;
}

BodyMesh body_from_gmsh(const GmshTets& t, std::vector<std::size_t>& used_tags) {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params, -1, -1, false, false);
  return body_from_tags(t, node_tags, coords, used_tags);
}

}  // namespace emc::mesh::detail
