#pragma once
// Private to the .msh parser: the state of one parse, shared by its section readers.
#include <string>

#include "msh_parser.hpp"
#include "msh_scanner.hpp"

namespace emc::mesh::msh {

/// The scanner, the data read so far, and which sections were read.
struct ParseState {
  ParseState(const std::string& text, const std::string& where) : s(text, where) {}
  Scanner s;
  MshData d;
  bool binary_file = false;
  bool have_names = false;
  bool have_entities = false;
  bool have_nodes = false;
  bool have_elements = false;
};

/// $Nodes (after its header line, up to its $EndNodes line): the node table of `p.d`, sorted
/// by tag; refuses duplicate tags, tags outside the declared range, non-finite coordinates.
void read_nodes(ParseState& p);

/// $Elements (after its header line, up to its $EndElements line): the element blocks of
/// `p.d`; refuses unknown element types, nodes not in $Nodes, duplicate element tags.
void read_elements(ParseState& p);

}  // namespace emc::mesh::msh
