#pragma once
// Reading and validating the Teuchos XML input against a schema. The input module knows no
// other module: each module declares its parameters, the app assembles them into the whole
// schema (emcontact/app/input_schema.hpp) and reads the input with it.
#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <string>
#include <vector>

namespace emc::input {

/// The names of the user-named sublists of `list` (a named section: `Bodies`, `Contact`,
/// `Dirichlet`), in the input's order; its plain parameters are skipped.
inline std::vector<std::string> sublist_names(const Teuchos::ParameterList& list) {
  std::vector<std::string> names;
  for (auto it = list.begin(); it != list.end(); ++it)
    if (list.isSublist(list.name(it))) names.push_back(list.name(it));
  return names;
}

/// A top-level section of the input. A fixed section (`Time`) is validated against `schema`;
/// a named section (`Bodies`, `Dirichlet`, `Contact`) holds user-named sublists, each validated
/// against the template `schema` and documented as `<name>/<placeholder>`.
struct Section {
  std::string name;
  std::string doc;
  Teuchos::RCP<const Teuchos::ParameterList> schema;
  std::string placeholder;  ///< "" for a fixed section, else e.g. "<body>"
  bool named() const { return !placeholder.empty(); }
};

/// Where the user gave the parameters the checks across parameters see: the input file's own
/// list (before the overrides and the defaults) and the paths the overrides set
/// ("Bodies/box/Mesh/file").
struct Given {
  const Teuchos::ParameterList& file;
  std::vector<std::string> override_paths;
  /// True if an override set the parameter or sublist at `path` (or one inside it).
  bool overridden(const std::string& path) const;
};

/// The whole input: its sections in documentation order, and the checks across parameters
/// (e.g. a contact pair names existing bodies) run once every section is validated and filled
/// in (`params`; `given` says where each value came from); they throw emc::InputError (see
/// detail::fail).
struct Schema {
  std::vector<Section> sections;
  std::function<void(const Teuchos::ParameterList& params, const Given& given,
                     const std::string& file)>
      check;
};

struct Input {
  Teuchos::RCP<Teuchos::ParameterList> params;  ///< validated, defaults filled in
  std::string file;                             ///< the XML file as given
  std::string dir;                              ///< its directory (relative mesh files)
};

/// Reads `file`, applies `overrides` ("Section/Sub/name=value", value parsed with the type the
/// schema gives that parameter), validates every section (each user-named sublist of a named
/// section against its template), fills defaults and runs `schema.check`. Throws
/// emc::InputError naming the file, the parameter path and what is allowed. Pure function of
/// its arguments (call on every rank).
Input read_input(const std::string& file, const std::vector<std::string>& overrides,
                 const Schema& schema);
/// The same for `text`, the contents of `file` read elsewhere (rank 0's copy on every rank).
Input read_input_text(const std::string& file, const std::string& text,
                      const std::vector<std::string>& overrides, const Schema& schema);
/// The contents of the input file `file`, for read_input_text; throws emc::InputError naming
/// it if it is missing, not a regular file or unreadable.
std::string read_input_file(const std::string& file);

/// The whole schema as one list, with one example entry for the user-named sublists
/// ("Bodies/<body>", "Dirichlet/<condition>", "Contact/<pair>").
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters(const Schema& schema);

/// Markdown documentation of every parameter (name, type, default, allowed values, doc string),
/// section by section, then an example input; used to generate inputs/README.md.
std::string schema_markdown(const Schema& schema);

}  // namespace emc::input
