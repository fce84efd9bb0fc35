#pragma once
#include <Teuchos_ParameterList.hpp>
#include <vector>

#include "emcontact/mesh/body_mesh.hpp"
#include "emcontact/types.hpp"

namespace emc::app {

/// Builds every body's mesh on rank 0 (Gmsh is not MPI-aware), checks its elements, and
/// broadcasts the meshes, or the error, to every rank (all ranks then throw the same error).
std::vector<mesh::BodyMesh> build_meshes(const Teuchos::ParameterList& params,
                                         const std::string& input_dir, const std::string& file,
                                         const Comm& comm);

}  // namespace emc::app
