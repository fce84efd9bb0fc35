// Markdown documentation of the schema (inputs/README.md is generated from it).
#include <algorithm>
#include <sstream>

#include "emcontact/input/detail.hpp"
#include "emcontact/input/input.hpp"

namespace emc::input {
namespace detail {
namespace {

using Teuchos::ParameterEntry;
using Teuchos::ParameterList;

/// Text for a Markdown table cell: one line, '|' escaped.
std::string cell(const std::string& text) {
  std::string s;
  for (char c : text) {
    if (c == '|') {
      s += "\\|";
    } else {
      s += (c == '\n' || c == '\r') ? ' ' : c;
    }
  }
  return s;
}

/// Text as lines of at most 100 characters (a longer word stands alone); blank lines between
/// paragraphs are kept.
std::string paragraph(const std::string& text) {
  std::string out, line, w;
  std::size_t from = 0;
  while (from <= text.size()) {
    const std::size_t to = std::min(text.find("\n\n", from), text.size());
    std::istringstream words(text.substr(from, to - from));
    while (words >> w) {
      if (!line.empty() && line.size() + 1 + w.size() > 100) {
        out += line + "\n";
        line.clear();
      }
      line += (line.empty() ? "" : " ") + w;
    }
    out += line;
    line.clear();
    if (to < text.size()) out += "\n\n";
    from = to + 2;
  }
  return out;
}

std::string default_cell(const ParameterEntry& e) {
  const auto& v = e.getAny(false);
  if (v.type() == typeid(std::string) && Teuchos::any_cast<std::string>(v).empty()) return "`\"\"`";
  return "`" + format_value(v, false) + "`";
}

/// One table row per parameter (and per pass-through sublist) of `list`.
std::string table(const ParameterList& list) {
  std::ostringstream rows;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const ParameterEntry& e = list.entry(it);
    const std::string name = "`" + cell(list.name(it)) + "`";
    if (!e.isList()) {
      rows << "| " << name << " | " << type_name(e.getAny(false)) << " | " << default_cell(e)
           << " | " << cell(allowed_markdown(e)) << " | " << cell(e.docString()) << " |\n";
    } else if (is_pass_through(list.sublist(list.name(it)))) {
      rows << "| " << name << " | sublist | empty | any content | " << cell(e.docString())
           << " |\n";
    }
  }
  if (rows.str().empty()) return "";
  return "| parameter | type | default | allowed | description |\n"
         "|---|---|---|---|---|\n" +
         rows.str() + "\n";
}

/// Documents `list` under the heading `path` (if it has parameters or a doc string), then its
/// validated sublists one level deeper.
void document(std::ostream& os, const ParameterList& list, const std::string& path,
              const std::string& doc, int level) {
  const std::string rows = table(list);
  if (!rows.empty() || !doc.empty()) {
    os << std::string(level, '#') << " `" << path << "`\n\n";
    if (!doc.empty()) os << paragraph(doc) << "\n\n";
    os << rows;
    ++level;
  }
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!list.entry(it).isList()) continue;
    const auto& sub = list.sublist(list.name(it));
    if (!is_pass_through(sub))
      document(os, sub, path + "/" + list.name(it), list.entry(it).docString(), level);
  }
}

}  // namespace

std::string example_xml() {
  return R"xml(<ParameterList name="example">
  <ParameterList name="Time">
    <Parameter name="dt" type="double" value="0.01"/>
    <Parameter name="end" type="double" value="1.0"/>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <ParameterList name="Mesh">
        <Parameter name="type" type="string" value="box"/>
        <Parameter name="lower corner" type="Array(double)" value="{0, 0, 0}"/>
        <Parameter name="upper corner" type="Array(double)" value="{1, 0.5, 0.3}"/>
        <Parameter name="size" type="double" value="0.1"/>
      </ParameterList>
      <ParameterList name="Material">
        <Parameter name="young" type="double" value="1e5"/>
        <Parameter name="poisson" type="double" value="0.3"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Loads">
    <Parameter name="gravity" type="Array(double)" value="{0, 0, -9.81}"/>
  </ParameterList>
  <ParameterList name="Dirichlet">
    <ParameterList name="clamped end">
      <Parameter name="body" type="string" value="block"/>
      <Parameter name="surface" type="string" value="xmin"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Solver">
    <ParameterList name="Linear">
      <Parameter name="type" type="string" value="gmres"/>
      <Parameter name="preconditioner" type="string" value="ilu"/>
      <ParameterList name="Ifpack2">
        <Parameter name="fact: iluk level-of-fill" type="int" value="1"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="directory" type="string" value="output"/>
    <Parameter name="every" type="int" value="10"/>
  </ParameterList>
</ParameterList>
)xml";
}

}  // namespace detail

std::string schema_markdown(const Schema& schema) {
  std::ostringstream os;
  for (const auto& s : schema.sections) {
    os << "## " << s.name << "\n\n" << detail::paragraph(s.doc) << "\n\n";
    if (s.named()) {
      detail::document(os, *s.schema, s.name + "/" + s.placeholder, "", 3);
    } else {
      os << detail::table(*s.schema);
      for (auto it = s.schema->begin(); it != s.schema->end(); ++it) {
        if (!s.schema->entry(it).isList()) continue;
        const auto& sub = s.schema->sublist(s.schema->name(it));
        if (!detail::is_pass_through(sub))
          detail::document(os, sub, s.name + "/" + s.schema->name(it),
                           s.schema->entry(it).docString(), 3);
      }
    }
  }
  os << "## Example\n\n"
     << "A block clamped at its `xmin` face, sagging under gravity (every parameter not "
        "given takes its default):\n\n```xml\n"
     << detail::example_xml() << "```\n";
  return os.str();
}

}  // namespace emc::input
