// Geometric queries on a BodyMesh: tet volumes and checks, boundary triangles, named surfaces.
#include "emcontact/mesh/body_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/vec3.hpp"
#include "internal.hpp"

namespace emc::mesh {
namespace {

using Tri = std::array<int, 3>;

Vec3 node(const BodyMesh& m, int i) {
  return {m.X[3 * i], m.X[3 * i + 1], m.X[3 * i + 2]};
}

/// One face of a tet: its nodes sorted (the key), the tet and the local index of the node
/// opposite the face.
struct Face {
  Tri key;
  int tet;
  int opposite;
};

bool key_less(const Face& a, const Face& b) {
  return a.key < b.key;
}

/// The three nodes of tet e other than local node `opposite`, in tet order.
Tri face_nodes(const BodyMesh& m, int e, int opposite) {
  Tri f{};
  int k = 0;
  for (int i = 0; i < 4; ++i) {
    if (i != opposite) f[k++] = m.tets[4 * e + i];
  }
  return f;
}

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

/// All 4 faces of every tet, sorted by key (then by tet, for determinism): O(n log n).
std::vector<Face> sorted_faces(const BodyMesh& m) {
  const int n = m.num_tets();
  std::vector<Face> faces;
  faces.reserve(4 * static_cast<std::size_t>(n));
  for (int e = 0; e < n; ++e) {
    for (int i = 0; i < 4; ++i) faces.push_back({sorted(face_nodes(m, e, i)), e, i});
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return a.key != b.key ? a.key < b.key : a.tet < b.tet;
  });
  return faces;
}

/// Triangle t oriented so that its normal (b-a)x(c-a) points away from node `apex`.
Tri orient_away(const BodyMesh& m, Tri t, int apex) {
  const Vec3 a = node(m, t[0]);
  const Vec3 n = cross(sub(node(m, t[1]), a), sub(node(m, t[2]), a));
  if (dot(n, sub(node(m, apex), a)) > 0.0) std::swap(t[1], t[2]);
  return t;
}

/// The face of `f`'s tet, oriented outward from that tet.
Tri outward_face(const BodyMesh& m, const Face& f) {
  return orient_away(m, face_nodes(m, f.tet, f.opposite), m.tets[4 * f.tet + f.opposite]);
}

std::string format_double(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double mean_abs_volume(const BodyMesh& m) {
  double sum = 0.0;
  for (int e = 0; e < m.num_tets(); ++e) sum += std::abs(tet_volume(m, e));
  return m.num_tets() > 0 ? sum / m.num_tets() : 0.0;
}

}  // namespace

double tet_volume(const BodyMesh& m, int e) {
  const int* t = &m.tets[4 * static_cast<std::size_t>(e)];
  const Vec3 a = node(m, t[0]);
  return dot(cross(sub(node(m, t[1]), a), sub(node(m, t[2]), a)), sub(node(m, t[3]), a)) / 6.0;
}

void check_tets(const BodyMesh& m, const std::string& where) {
  check_tets(m, where, std::vector<std::size_t>());
}

void check_tets(const BodyMesh& m, const std::string& where,
                const std::vector<std::size_t>& element_ids) {
  if (m.num_tets() == 0) return;  // a rigid surface: no volume elements to check
  const double mean = mean_abs_volume(m);
  for (int e = 0; e < m.num_tets(); ++e) {
    const double v = tet_volume(m, e);
    const bool degenerate = !(std::abs(v) > 1e-12 * mean);  // also catches NaN
    if (!degenerate && v > 0.0) continue;
    const std::size_t id = element_ids.empty() ? static_cast<std::size_t>(e) + 1 : element_ids[e];
    const std::string head = where + ": element " + std::to_string(id) + " is ";
    if (degenerate) {
      throw InputError(head + "degenerate (volume " + format_double(v) + ", mean " +
                       format_double(mean) +
                       "); every tetrahedron must have a volume above 1e-12 of the mean");
    }
    throw InputError(head + "inverted (volume " + format_double(v) +
                     "); every tetrahedron must have positive volume");
  }
}

std::vector<std::array<int, 3>> boundary_triangles(const BodyMesh& m) {
  const std::vector<Face> faces = sorted_faces(m);
  std::vector<Tri> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) out.push_back(outward_face(m, faces[i]));
    i = j;
  }
  detail::sort_triangles(out);
  return out;
}

std::vector<int> surface_nodes(const BodyMesh& m, const std::string& name,
                               const std::string& where) {
  const auto it = m.surfaces.find(name);
  if (it == m.surfaces.end() && name == "boundary" && is_rigid(m)) {
    std::vector<int> all(m.num_nodes());
    for (int i = 0; i < m.num_nodes(); ++i) all[i] = i;
    return all;
  }
  std::vector<Tri> boundary;
  if (it == m.surfaces.end() && name == "boundary") boundary = boundary_triangles(m);
  if (it == m.surfaces.end() && name != "boundary") {
    std::string names;
    for (const auto& s : m.surfaces) names += "'" + s.first + "', ";
    throw InputError(where + ": unknown surface '" + name + "'; the mesh has " + names +
                     "and 'boundary' (all boundary triangles)");
  }
  const std::vector<Tri>& tris = it != m.surfaces.end() ? it->second : boundary;
  std::vector<int> nodes;
  nodes.reserve(3 * tris.size());
  for (const Tri& t : tris) nodes.insert(nodes.end(), t.begin(), t.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

namespace detail {

std::vector<std::array<int, 3>> orient_on_body(const BodyMesh& m, const std::vector<Tri>& tris) {
  const std::vector<Face> faces = sorted_faces(m);
  std::vector<Tri> out;
  out.reserve(tris.size());
  for (const Tri& t : tris) {
    const Face probe{sorted(t), 0, 0};
    const auto range = std::equal_range(faces.begin(), faces.end(), probe, key_less);
    const auto count = range.second - range.first;
    if (count == 1) out.push_back(outward_face(m, *range.first));
    if (count >= 2) out.push_back(t);  // internal surface: keep the given orientation
  }
  return out;
}

std::array<int, 3> canonical_rotation(const std::array<int, 3>& t) {
  const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

void sort_triangles(std::vector<std::array<int, 3>>& tris) {
  for (Tri& t : tris) t = canonical_rotation(t);
  std::sort(tris.begin(), tris.end());
}

}  // namespace detail
}  // namespace emc::mesh
