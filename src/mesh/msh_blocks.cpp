// $Nodes and $Elements of a .msh 4.1 file: entity blocks of nodes and of elements, validated
// against the section headers, $Entities and each other.
#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <sstream>

#include "msh_parse_state.hpp"

namespace emc::mesh::msh {
namespace {

/// At most this many nodes or elements (a BodyMesh numbers nodes and tets with int).
constexpr std::uint64_t kMaxCount = INT_MAX / 4;

/// The header "numEntityBlocks numItems minTag maxTag" of $Nodes or $Elements.
struct BlocksHeader {
  std::uint64_t blocks = 0;
  std::uint64_t total = 0;
  std::uint64_t min_tag = 0;
  std::uint64_t max_tag = 0;
};

/// Reads and checks a section header; an item takes at least `ascii_each` bytes in an ASCII
/// file, `binary_each` in a binary one.
BlocksHeader read_header(Scanner& s, const std::string& item, std::size_t ascii_each,
                         std::size_t binary_each) {
  BlocksHeader h;
  h.blocks = s.size("the number of entity blocks");
  h.total = s.size("the total count");
  h.min_tag = s.size("the minimum tag");
  h.max_tag = s.size("the maximum tag");
  s.check_count(h.blocks, 8, 20, "the number of entity blocks");
  s.check_count(h.total, ascii_each, binary_each, "the number of " + item + "s");
  if (h.total > kMaxCount) {
    s.fail(std::to_string(h.total) + " " + item + "s; at most " + std::to_string(kMaxCount) +
           " are supported");
  }
  if (h.total > 0 && (h.min_tag == 0 || h.min_tag > h.max_tag)) {
    s.fail("the " + item + " tag range [" + std::to_string(h.min_tag) + ", " +
           std::to_string(h.max_tag) + "] is invalid; tags are positive and min <= max");
  }
  s.end_line("the section header");
  return h;
}

/// The entity (dimension, tag) of a block header. Refuses an entity $Entities does not
/// declare; without $Entities the entity is created (as Gmsh does), with no physical group.
MshData::DimTag read_block_entity(ParseState& p) {
  Scanner& s = p.s;
  const int dim = s.integer("the entity dimension");
  if (dim < 0 || dim > 3) s.fail("entity dimension " + std::to_string(dim) + "; allowed: 0 to 3");
  const int tag = s.integer("the entity tag");
  if (tag <= 0) s.fail("entity tag " + std::to_string(tag) + "; entity tags are positive");
  const MshData::DimTag key(dim, tag);
  if (p.have_entities && p.d.entity_physicals.count(key) == 0) {
    s.fail("the block's entity of dimension " + std::to_string(dim) + " and tag " +
           std::to_string(tag) + " is not in $Entities");
  }
  if (!p.have_entities) p.d.entity_physicals.emplace(key, std::vector<int>());
  return key;
}

/// Refuses a tag outside the header's range.
void check_tag(Scanner& s, const BlocksHeader& h, std::uint64_t tag, const char* item) {
  if (tag >= h.min_tag && tag <= h.max_tag) return;
  s.fail(std::string(item) + " tag " + std::to_string(tag) + " is outside the range [" +
         std::to_string(h.min_tag) + ", " + std::to_string(h.max_tag) + "] of the section header");
}

/// Refuses a block of `n` items when the blocks before hold `read` of the header's total.
void check_block_total(Scanner& s, const BlocksHeader& h, std::uint64_t n, std::size_t read,
                       const char* items) {
  if (n <= h.total - read) return;
  s.fail("the blocks hold more " + std::string(items) + " than the " + std::to_string(h.total) +
         " of the section header");
}

/// The nodes of $Nodes in file order.
struct NodeList {
  std::vector<std::size_t> tags;
  std::vector<double> xyz;
};

/// The coordinates "x y z [u [v [w]]]" of the `n` nodes of a block whose tags were read last;
/// `params` parametric coordinates per node are skipped.
void read_node_coordinates(Scanner& s, std::uint64_t n, std::size_t params, NodeList& nodes) {
  const std::size_t first = nodes.tags.size() - n;
  for (std::uint64_t i = 0; i < n; ++i) {
    double x[3];
    for (double& v : x) v = s.real("a node coordinate");
    for (std::size_t k = 0; k < params; ++k) (void)s.real("a parametric coordinate");
    for (double v : x) {
      if (std::isfinite(v)) continue;
      std::ostringstream msg;
      msg << "node " << nodes.tags[first + i] << " has the coordinate " << v
          << "; coordinates must be finite numbers";
      s.fail(msg.str());
    }
    s.end_line("the node coordinates");
    nodes.xyz.insert(nodes.xyz.end(), x, x + 3);
  }
}

/// One node block: header, tags, then coordinates (and parametric coordinates, skipped).
void read_node_block(ParseState& p, const BlocksHeader& h, NodeList& nodes) {
  Scanner& s = p.s;
  const MshData::DimTag entity = read_block_entity(p);
  const int parametric = s.integer("the parametric flag");
  if (parametric != 0 && parametric != 1) {
    s.fail("parametric flag " + std::to_string(parametric) + "; allowed: 0 or 1");
  }
  const std::uint64_t n = s.size("the number of nodes in the block");
  const std::size_t params = parametric ? static_cast<std::size_t>(entity.first) : 0;
  s.check_count(n, 8 + 2 * params, 32 + 8 * params, "the number of nodes in the block");
  check_block_total(s, h, n, nodes.tags.size(), "nodes");
  s.end_line("the block header");
  for (std::uint64_t i = 0; i < n; ++i) {
    nodes.tags.push_back(s.size("a node tag"));
    check_tag(s, h, nodes.tags.back(), "node");
    s.end_line("the node tag");
  }
  read_node_coordinates(s, n, params, nodes);
}

/// The node table of `d`, sorted by tag; refuses a tag given twice.
void sort_nodes(const Scanner& s, const NodeList& nodes, MshData& d) {
  std::vector<std::size_t> order(nodes.tags.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return nodes.tags[a] < nodes.tags[b]; });
  d.node_tags.resize(order.size());
  d.coords.resize(3 * order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    d.node_tags[i] = nodes.tags[order[i]];
    std::copy_n(&nodes.xyz[3 * order[i]], 3, &d.coords[3 * i]);
    if (i > 0 && d.node_tags[i] == d.node_tags[i - 1]) {
      s.fail_section("node tag " + std::to_string(d.node_tags[i]) + " is defined twice");
    }
  }
}

/// One element "tag node..." of type `t`; its tags go to `keep` if not null.
void read_element(Scanner& s, const MshData& d, const BlocksHeader& h, const ElementType& t,
                  ElementBlock* keep, std::vector<std::size_t>& all_tags) {
  const std::uint64_t tag = s.size("an element tag");
  check_tag(s, h, tag, "element");
  all_tags.push_back(tag);
  if (keep) keep->element_tags.push_back(tag);
  for (int k = 0; k < t.num_nodes; ++k) {
    const std::uint64_t node = s.size("a node tag of the element");
    if (!std::binary_search(d.node_tags.begin(), d.node_tags.end(), node)) {
      s.fail("element " + std::to_string(tag) + " refers to node " + std::to_string(node) +
             ", which is not in $Nodes");
    }
    if (keep) keep->node_tags.push_back(node);
  }
  if (s.try_end_line()) return;
  s.fail("element " + std::to_string(tag) + " has more than the " + std::to_string(t.num_nodes) +
         " nodes of element type " + std::to_string(t.type) + " ('" + t.name + "')");
}

/// The element type of a block header on an entity of dimension `dim`.
const ElementType& read_element_type(Scanner& s, int dim) {
  const int type = s.integer("the element type");
  const ElementType* t = element_type(type);
  if (!t) {
    s.fail("unknown element type " + std::to_string(type) +
           "; known: Gmsh's types 1 to 33, 92 and 93 (read_msh uses 2, the 3-node triangle, "
           "and 4, the 4-node tetrahedron)");
  }
  if (t->dim != dim) {
    s.fail("element type " + std::to_string(type) + " ('" + t->name + "') has dimension " +
           std::to_string(t->dim) + ", but the block's entity has dimension " +
           std::to_string(dim));
  }
  return *t;
}

/// One element block; keeps the tags of 3-node triangles and 4-node tets only.
void read_element_block(ParseState& p, const BlocksHeader& h, std::vector<std::size_t>& all_tags) {
  Scanner& s = p.s;
  const MshData::DimTag entity = read_block_entity(p);
  const ElementType& t = read_element_type(s, entity.first);
  const std::uint64_t n = s.size("the number of elements in the block");
  const std::size_t each = 1 + static_cast<std::size_t>(t.num_nodes);
  s.check_count(n, 2 * each, 8 * each, "the number of elements in the block");
  check_block_total(s, h, n, all_tags.size(), "elements");
  s.end_line("the block header");
  ElementBlock block;
  block.dim = entity.first;
  block.entity = entity.second;
  block.type = t.type;
  block.count = n;
  const bool keep = t.type == 2 || t.type == 4;
  if (keep) {  // n is bounded by the file size (check_count)
    block.element_tags.reserve(n);
    block.node_tags.reserve(n * static_cast<std::size_t>(t.num_nodes));
  }
  for (std::uint64_t i = 0; i < n; ++i)
    read_element(s, p.d, h, t, keep ? &block : nullptr, all_tags);
  p.d.entity_blocks[entity].push_back(p.d.blocks.size());
  p.d.blocks.push_back(std::move(block));
}

}  // namespace

void read_nodes(ParseState& p) {
  Scanner& s = p.s;
  const BlocksHeader h = read_header(s, "node", 8, 32);
  NodeList nodes;
  for (std::uint64_t b = 0; b < h.blocks; ++b) read_node_block(p, h, nodes);
  if (nodes.tags.size() != h.total) {
    s.fail("the blocks hold " + std::to_string(nodes.tags.size()) + " nodes, the section header " +
           "says " + std::to_string(h.total));
  }
  sort_nodes(s, nodes, p.d);
}

void read_elements(ParseState& p) {
  Scanner& s = p.s;
  const BlocksHeader h = read_header(s, "element", 4, 16);
  std::vector<std::size_t> tags;
  for (std::uint64_t b = 0; b < h.blocks; ++b) read_element_block(p, h, tags);
  if (tags.size() != h.total) {
    s.fail("the blocks hold " + std::to_string(tags.size()) + " elements, the section header " +
           "says " + std::to_string(h.total));
  }
  std::sort(tags.begin(), tags.end());
  const auto twice = std::adjacent_find(tags.begin(), tags.end());
  if (twice != tags.end())
    s.fail_section("element tag " + std::to_string(*twice) + " is used twice");
}

}  // namespace emc::mesh::msh
