#pragma once
// Built-in meshes (through Gmsh's C++ API, OpenCASCADE kernel) and the Gmsh .msh reader.
#include <Teuchos_ParameterList.hpp>

#include "emcontact/mesh/body_mesh.hpp"

namespace emc::mesh {

/// Valid parameters of a body's `Mesh` sublist (with defaults, validators, doc strings).
Teuchos::RCP<const Teuchos::ParameterList> valid_mesh_parameters();

/// Builds the mesh a validated `Mesh` sublist describes. `input_dir` resolves relative file
/// names; `where` (e.g. "input.xml: Bodies/ball/Mesh") prefixes every error. Call on one rank
/// (Gmsh is not MPI-aware); the caller broadcasts the result.
BodyMesh build_mesh(const Teuchos::ParameterList& mesh_params, const std::string& input_dir,
                    const std::string& where);

/// Reads a Gmsh .msh file (format 4.1) through Gmsh's API: all 4-node tets (or those of the
/// physical volume `volume` if not empty) and every physical surface as a named surface.
BodyMesh read_msh(const std::string& file, const std::string& volume, const std::string& where);

}  // namespace emc::mesh
