#pragma once
// Built-in meshes (through Gmsh's C++ API, OpenCASCADE kernel), the rigid surfaces (`plane`,
// `rectangle`) and the reader of Gmsh .msh files (our own strict parser).
#include <Teuchos_ParameterList.hpp>
#include <array>
#include <string>
#include <vector>

#include "emcontact/mesh/body_mesh.hpp"

namespace emc::mesh {

/// The values of `Mesh/type` (its validator's: Teuchos::getIntegralValue<MeshType>).
enum class MeshType { box, cylinder, hollow_cylinder, spherical_shell, plane, rectangle, file };

/// Valid parameters of a body's `Mesh` sublist (with defaults, validators, doc strings).
Teuchos::RCP<const Teuchos::ParameterList> valid_mesh_parameters();

/// The values of `Mesh/type` that read the `Mesh` parameter `parameter` (each type reads its
/// own: the corners of a box, the radii of a shell...); empty for `type` itself and for a name
/// that is not a `Mesh` parameter.
std::vector<std::string> types_reading(const std::string& parameter);

/// True for the `type` values that always give a rigid surface (no tets): "plane", "rectangle".
/// (A "file" without tetrahedra is one too, which is only known once it is read.)
bool is_rigid_surface_type(MeshType type);

/// At most this many tetrahedra in all the bodies of a run together (generated meshes and
/// files). Rank 0 builds or reads the whole mesh and holds it, in 32-bit node ids and 32-bit
/// tet indices, until it has handed out the parts; 4 ids per tet and 3 dofs per node (about a
/// fifth of the tets) then stay well below 2^31. What each rank needs beyond that, including
/// rank 0's mesher, is checked against its memory (app::check_memory).
constexpr double kMaxTets = 2e8;

/// About the number of tetrahedra build_mesh makes of a generated volume (type box, cylinder,
/// hollow cylinder, spherical shell: 8.5 V / size^3, regular tets of edge `size`), after
/// checking its parameters as build_mesh does (InputError); 0 for the other types.
double estimated_tets(const Teuchos::ParameterList& mesh_params, const std::string& where);

/// Builds the mesh a validated `Mesh` sublist describes. `input_dir` resolves relative file
/// names; `where` (e.g. "input.xml: Bodies/ball/Mesh") prefixes every error. Call on one rank
/// (Gmsh is not MPI-aware); the caller broadcasts the result.
BodyMesh build_mesh(const Teuchos::ParameterList& mesh_params, const std::string& input_dir,
                    const std::string& where);

/// Reads a Gmsh .msh file (format 4.1) with our strict parser (src/mesh/msh_parser.hpp: ASCII
/// or binary, every count, tag and reference checked, no Gmsh involved): all 4-node tets (or
/// those of the physical volume `volume` if not empty) and every physical surface as a named
/// surface. A file with no tets at all but 3-node triangles (and `volume` empty) is a rigid
/// surface: the triangles' nodes, no tets, every physical surface by name plus `surface` (all
/// triangles), oriented as in the file.
BodyMesh read_msh(const std::string& file, const std::string& volume, const std::string& where);

/// The numbers of cells (n1, n2) of a grid on an l1 x l2 rectangle with cells of edge about
/// `size`: ceil(l / size) each (at least 1), but at most kMaxGridCells cells in all (200 x 200
/// on a square): larger, still about square cells if `size` is too small for the extents.
constexpr double kMaxGridCells = 40000;
std::array<int, 2> grid_cells(double l1, double l2, double size);

}  // namespace emc::mesh
