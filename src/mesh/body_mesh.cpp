// Geometric queries on a BodyMesh: tet volumes and checks, boundary triangles, named surfaces.
#include "emcontact/mesh/body_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
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

/// The median of `v` (the upper one for an even count; 0 if empty). A few wild values (an
/// element with a node far away) do not move it, as they move the mean.
double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double median_abs_volume(const BodyMesh& m) {
  std::vector<double> v(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) v[e] = std::abs(tet_volume(m, e));
  return median(std::move(v));
}

/// The longest edge of tet e.
double longest_edge(const BodyMesh& m, int e) {
  const int* t = &m.tets[4 * static_cast<std::size_t>(e)];
  double l = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) l = std::max(l, norm(sub(node(m, t[i]), node(m, t[j]))));
  return l;
}

/// Shape quality of tet e: its volume over that of the regular tet on its longest edge (1 for
/// a regular tet, about its thickness over its longest edge for a flat one).
double shape_quality(const BodyMesh& m, int e) {
  const double l = longest_edge(m, e);
  return 6.0 * std::sqrt(2.0) * std::abs(tet_volume(m, e)) / (l * l * l);
}

std::size_t element_id(const std::vector<std::size_t>& element_ids, int e) {
  return element_ids.empty() ? static_cast<std::size_t>(e) + 1 : element_ids[e];
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
  const double typical = median_abs_volume(m);
  for (int e = 0; e < m.num_tets(); ++e) {
    const double v = tet_volume(m, e);
    const bool degenerate = !(std::abs(v) > kMinVolumeRatio * typical);  // also catches NaN
    if (!degenerate && v > 0.0 && std::isfinite(v)) continue;
    const std::string head =
        where + ": element " + std::to_string(element_id(element_ids, e)) + " is ";
    if (!std::isfinite(v))
      throw InputError(head +
                       "too large: its volume is not a finite number (its nodes lie "
                       "too far apart); every tetrahedron must have a finite volume");
    if (degenerate) {
      throw InputError(head + "degenerate (volume " + format_double(v) + ", median " +
                       format_double(typical) +
                       "); every tetrahedron must have a volume above 1e-12 of the median");
    }
    throw InputError(head + "inverted (volume " + format_double(v) +
                     "); every tetrahedron must have positive volume");
  }
  for (int e = 0; e < m.num_tets(); ++e) {
    const double q = shape_quality(m, e);
    if (q >= kMinShapeQuality) continue;
    throw InputError(where + ": element " + std::to_string(element_id(element_ids, e)) +
                     " is flat (its volume is " + format_double(q) +
                     " of a regular tetrahedron's on its longest edge " +
                     format_double(longest_edge(m, e)) +
                     "; a mesh squashed in one direction?); every tetrahedron must reach 1e-6 "
                     "of it (a flatter one makes the Newton matrix too ill-conditioned to "
                     "solve)");
  }
}

void check_nodes(const BodyMesh& m, const std::string& where,
                 const std::vector<std::size_t>& node_ids) {
  const auto id = [&](int n) {
    return node_ids.empty() ? static_cast<std::size_t>(n) + 1 : node_ids[n];
  };
  for (int n = 0; n < m.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      const double x = m.X[3 * static_cast<std::size_t>(n) + c];
      if (std::abs(x) <= kMaxCoordinate) continue;  // also refuses NaN
      throw InputError(where + ": node " + std::to_string(id(n)) + " has the coordinate " +
                       "xyz"[c] + " = " + format_double(x) +
                       "; coordinates must be finite numbers of magnitude at most 1e30");
    }
  if (m.num_tets() == 0) return;
  std::vector<double> edges(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) edges[e] = longest_edge(m, e);
  const double h = median(std::move(edges));
  Vec3 centre{};
  for (int c = 0; c < 3; ++c) {
    std::vector<double> x(m.num_nodes());
    for (int n = 0; n < m.num_nodes(); ++n) x[n] = m.X[3 * static_cast<std::size_t>(n) + c];
    centre[c] = median(std::move(x));
  }
  for (int n = 0; n < m.num_nodes(); ++n) {
    const double d = norm(sub(node(m, n), centre));
    if (!(d > kMaxNodeDistance * h)) continue;
    throw InputError(where + ": node " + std::to_string(id(n)) + " lies " + format_double(d) +
                     " from the mesh's median node position, more than 1e9 times the median "
                     "longest edge of its tetrahedra (" +
                     format_double(h) + "): a stray node, or coordinates in other units?");
  }
}

void check_distinct_tets(const BodyMesh& m, const std::string& where,
                         const std::vector<std::size_t>& element_ids) {
  // nodes at exactly the same coordinates share a point index
  std::vector<int> order(m.num_nodes()), point(m.num_nodes());
  for (int n = 0; n < m.num_nodes(); ++n) order[n] = n;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return node(m, a) < node(m, b) || (node(m, a) == node(m, b) && a < b);
  });
  for (int k = 0, p = 0; k < m.num_nodes(); ++k) {
    if (k > 0 && node(m, order[k]) != node(m, order[k - 1])) ++p;
    point[order[k]] = p;
  }
  struct Key {
    std::array<int, 4> points;
    int tet;
  };
  std::vector<Key> keys(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) {
    for (int i = 0; i < 4; ++i) keys[e].points[i] = point[m.tets[4 * e + i]];
    std::sort(keys[e].points.begin(), keys[e].points.end());
    keys[e].tet = e;
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.points != b.points ? a.points < b.points : a.tet < b.tet;
  });
  for (std::size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].points != keys[k - 1].points) continue;
    int a = keys[k - 1].tet, b = keys[k].tet;
    if (element_id(element_ids, a) > element_id(element_ids, b)) std::swap(a, b);
    std::array<int, 4> na{}, nb{};
    std::copy_n(&m.tets[4 * a], 4, na.begin());
    std::copy_n(&m.tets[4 * b], 4, nb.begin());
    std::sort(na.begin(), na.end());
    std::sort(nb.begin(), nb.end());
    const std::string pair = "elements " + std::to_string(element_id(element_ids, a)) + " and " +
                             std::to_string(element_id(element_ids, b));
    if (na == nb)
      throw InputError(where + ": " + pair +
                       " have the same 4 nodes (an element given twice: its mass and stiffness "
                       "would count twice); every tetrahedron must be given once");
    throw InputError(where + ": " + pair +
                     " lie on the same 4 points through different nodes (a second copy of the "
                     "mesh on top of the first?); every tetrahedron must be given once");
  }
}

std::vector<std::array<int, 3>> boundary_triangles(const BodyMesh& m) {
  if (m.dropped_tets >= 0 || !m.boundary.empty()) return m.boundary;  // kept by drop_tets
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

void drop_tets(BodyMesh& m) {
  if (m.dropped_tets >= 0 || m.tets.empty()) return;
  if (m.boundary.empty()) m.boundary = boundary_triangles(m);
  m.dropped_tets = m.num_tets();
  std::vector<int>().swap(m.tets);
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
    std::string names;  // at most 10 listed
    int listed = 0;
    for (const auto& s : m.surfaces)
      if (listed++ < 10) names += "'" + input::echo(s.first) + "', ";
    if (listed > 10) names += std::to_string(listed - 10) + " more ";
    throw InputError(where + ": unknown surface '" + input::echo(name) + "'; the mesh has " +
                     names + "and 'boundary' (all boundary triangles)");
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
