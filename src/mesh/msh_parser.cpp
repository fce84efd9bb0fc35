// The .msh 4.1 parser: the section loop, $MeshFormat, $PhysicalNames and $Entities, and the
// skipping of the sections read_msh does not use. $Nodes and $Elements: msh_blocks.cpp.
#include "msh_parser.hpp"

#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
#include "msh_parse_state.hpp"

namespace emc::mesh::msh {
namespace {

const char* const kEntityKinds[4] = {"point", "curve", "surface", "volume"};

/// The version, file type and data size of $MeshFormat (and, in a binary file, the int 1 that
/// tells the byte order); switches the scanner to binary-file positions.
void read_format(ParseState& p) {
  Scanner& s = p.s;
  const double version = s.real("the format version");
  if (version != 4.1) {
    std::ostringstream v;
    v << version;
    s.fail("format version " + v.str() +
           "; only version 4.1 is supported (write format 4.1: gmsh -3 -format msh41)");
  }
  const int type = s.integer("the file type");
  if (type != 0 && type != 1) {
    s.fail("file type " + std::to_string(type) + "; allowed: 0 (ASCII) or 1 (binary)");
  }
  const int data_size = s.integer("the data size");
  if (data_size != 8) {
    s.fail("data size " + std::to_string(data_size) +
           "; only 8 (64-bit size_t, as Gmsh writes on 64-bit systems) is supported");
  }
  s.end_line("the data size");
  if (type == 0) return;
  p.binary_file = true;
  s.set_binary(true);
  const int one = s.integer("the byte order check (the int 1)");
  if (one == 0x01000000) {
    s.fail(
        "a big-endian binary file; only little-endian binary files are supported (or write "
        "ASCII: gmsh -3 -format msh41 without -bin)");
  }
  if (one != 1)
    s.fail("expected the int 1 after the header of a binary file, found " + std::to_string(one));
  s.set_binary(false);
  s.set_binary_file(true);
}

/// $PhysicalNames (ASCII in binary files too): "dim tag "name"" lines.
void read_physical_names(ParseState& p) {
  Scanner& s = p.s;
  const std::uint64_t n = s.size("the number of physical names");
  s.check_count(n, 7, 7, "the number of physical names");
  s.end_line("the number of physical names");
  for (std::uint64_t i = 0; i < n; ++i) {
    const int dim = s.integer("the dimension of a physical group");
    if (dim < 0 || dim > 3) s.fail("dimension " + std::to_string(dim) + "; allowed: 0 to 3");
    const int tag = s.integer("a physical tag");
    if (tag <= 0) s.fail("physical tag " + std::to_string(tag) + "; physical tags are positive");
    const std::string name = s.quoted("the physical name");
    if (!p.d.physical_names.emplace(MshData::DimTag(dim, tag), name).second) {
      s.fail("a second name for the physical group of dimension " + std::to_string(dim) +
             " and tag " + std::to_string(tag));
    }
    s.end_line("the physical name");
  }
}

/// A list "count tag..." of an entity; the tags (positive ones only if `positive`).
std::vector<int> read_tag_list(Scanner& s, const char* count_what, const char* tag_what,
                               bool positive) {
  const std::uint64_t n = s.size(count_what);
  s.check_count(n, 2, 4, count_what);
  std::vector<int> tags;
  tags.reserve(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    tags.push_back(s.integer(tag_what));
    if (positive && tags.back() <= 0) {
      s.fail(std::string(tag_what) + " " + std::to_string(tags.back()) + "; it must be positive");
    }
  }
  return tags;
}

/// One entity of dimension `dim`: its tag and physical tags (coordinates, bounding box and
/// bounding entities are read and ignored).
void read_entity(ParseState& p, int dim) {
  Scanner& s = p.s;
  const int tag = s.integer("an entity tag");
  if (tag <= 0)
    s.fail(std::string(kEntityKinds[dim]) + " tag " + std::to_string(tag) +
           "; entity tags are positive");
  for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) {
    (void)s.real(dim == 0 ? "a point coordinate" : "a bounding box coordinate");
  }
  std::vector<int> physicals =
      read_tag_list(s, "the number of physical tags", "a physical tag", true);
  if (dim > 0) {
    (void)read_tag_list(s, "the number of bounding entities", "a bounding entity tag", false);
  }
  if (!p.d.entity_physicals.emplace(MshData::DimTag(dim, tag), std::move(physicals)).second) {
    s.fail("a second " + std::string(kEntityKinds[dim]) + " " + std::to_string(tag));
  }
  s.end_line("the entity");
}

/// $Entities: points, curves, surfaces and volumes with their physical tags.
void read_entities(ParseState& p) {
  Scanner& s = p.s;
  std::uint64_t counts[4];
  for (int dim = 0; dim < 4; ++dim) {
    counts[dim] = s.size("the number of entities");
    s.check_count(counts[dim], dim == 0 ? 10 : 18, dim == 0 ? 36 : 68,
                  std::string("the number of ") + kEntityKinds[dim] + "s");
  }
  s.end_line("the numbers of entities");
  for (int dim = 0; dim < 4; ++dim) {
    for (std::uint64_t i = 0; i < counts[dim]; ++i) read_entity(p, dim);
  }
}

/// Moves past the line "$End<name>" (blank lines before it allowed); refuses anything else.
void expect_end(Scanner& s, const std::string& name) {
  s.skip_space();
  const std::size_t at = s.position();
  const std::string line = s.line();
  if (line == "$End" + name) return;
  s.seek(at);
  if (line.empty())
    s.fail("expected $End" + name + ", found the end of the file (truncated file?)");
  s.fail("expected $End" + name + ", found " + Scanner::quote(line) +
         " (do the counts of the section match its data?)");
}

/// Moves past the line "$End<name>" of a section read_msh does not use.
void skip_section(Scanner& s, const std::string& name) {
  const std::string marker = "$End" + name;
  const std::string& text = s.text();
  for (std::size_t at = s.position();; ++at) {
    at = text.find(marker, at);
    if (at == std::string::npos) {
      s.fail("section $" + input::echo(name) + " has no " + input::echo(marker) +
             " line (truncated file?)");
    }
    const std::size_t end = at + marker.size();
    const bool line_start = at == 0 || text[at - 1] == '\n';
    const bool line_end =
        end == text.size() || std::string(" \t\r\n").find(text[end]) != std::string::npos;
    if (!line_start || !line_end) continue;
    s.seek(at);
    (void)s.line();
    return;
  }
}

/// Refuses a second $<name>, or one after the section `later` that must follow it.
void check_order(ParseState& p, bool& seen, bool later_seen, const std::string& name,
                 const std::string& later) {
  if (seen) p.s.fail("a second $" + name + " section; a mesh file has at most one");
  if (later_seen) p.s.fail("$" + name + " after $" + later + "; it must come before");
  seen = true;
}

/// Refuses the section "$<name>" (the scanner is at its header line) if it is a second one,
/// out of order or a partitioned mesh; marks it as read.
void check_section(ParseState& p, const std::string& name) {
  Scanner& s = p.s;
  if (name == "MeshFormat") s.fail("a second $MeshFormat section");
  if (name == "PartitionedEntities") {
    s.fail("partitioned meshes are not supported; write the mesh without partitioning it");
  }
  if (name == "PhysicalNames") check_order(p, p.have_names, false, name, "");
  if (name == "Entities") check_order(p, p.have_entities, p.have_nodes, name, "Nodes");
  if (name == "Nodes") check_order(p, p.have_nodes, p.have_elements, name, "Elements");
  if (name == "Elements") {
    check_order(p, p.have_elements, false, name, "");
    if (!p.have_nodes) s.fail("$Elements before $Nodes; the nodes must come first");
  }
}

/// Reads the section "$<name>" whose header line was just read, up to its $End line; skips
/// the sections read_msh does not use.
void read_section(ParseState& p, const std::string& name) {
  Scanner& s = p.s;
  if (name == "PhysicalNames") {
    read_physical_names(p);  // ASCII in binary files too
  } else if (name == "Entities" || name == "Nodes" || name == "Elements") {
    s.set_binary(p.binary_file);
    if (name == "Entities") read_entities(p);
    if (name == "Nodes") read_nodes(p);
    if (name == "Elements") read_elements(p);
    s.set_binary(false);
  } else {
    skip_section(s, name);
    return;
  }
  expect_end(s, name);
}

/// The entities of every physical group, from the entities' physical tags.
void index_groups(MshData& d) {
  for (const auto& e : d.entity_physicals) {  // by increasing (dim, tag): sorted lists
    for (int group : e.second) {
      std::vector<int>& entities = d.group_entities[{e.first.first, group}];
      if (entities.empty() || entities.back() != e.first.second) {
        entities.push_back(e.first.second);
      }
    }
  }
}

}  // namespace

MshData parse_msh(const std::string& text, const std::string& where) {
  ParseState p(text, where);
  Scanner& s = p.s;
  s.skip_space();
  if (s.line() != "$MeshFormat") {
    throw InputError(where +
                     " is not a Gmsh .msh file (it must start with $MeshFormat; write format "
                     "4.1, e.g. gmsh -3 -format msh41 body.geo)");
  }
  s.set_section("MeshFormat");
  read_format(p);
  expect_end(s, "MeshFormat");
  while (!s.at_end()) {
    s.set_section("");
    const std::size_t at = s.position();
    const std::string header = s.line();
    s.seek(at);
    if (header.size() < 2 || header[0] != '$' || header.compare(0, 4, "$End") == 0) {
      s.fail("expected a section header such as $Nodes, found " + Scanner::quote(header));
    }
    s.set_section(header.substr(1));
    check_section(p, header.substr(1));
    (void)s.line();
    read_section(p, header.substr(1));
  }
  index_groups(p.d);
  return std::move(p.d);
}

}  // namespace emc::mesh::msh
