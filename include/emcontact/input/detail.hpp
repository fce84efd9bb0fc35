#pragma once
// Internals of the input module, declared for its sources, the app's cross-checks of the input
// (emcontact/app/input_schema.hpp) and unit tests.
#include <Teuchos_ParameterList.hpp>
#include <optional>
#include <string>
#include <vector>

#include "emcontact/input/input.hpp"

namespace emc::input::detail {

/// What is wrong with one value, and what is allowed instead.
struct Problem {
  std::string what;
  std::string allowed;
};

// --- describing schema entries (describe.cpp) ---

/// The Teuchos/XML type name of a value: "double", "int", "string", "bool", "Array(double)".
std::string type_name(const Teuchos::any& value);
/// A value as the user writes it: shortest round-trip doubles, {x, y, z} arrays, quoted strings
/// if `quote_strings`.
std::string format_value(const Teuchos::any& value, bool quote_strings = true);
/// input::echo(text): escaped, and if long its first 80 characters, "..." and its length
/// (values echoed in messages).
std::string shorten(const std::string& text);
/// The shortest decimal that reads back as exactly `x`.
std::string format_double(double x);
/// What a schema entry accepts, as a phrase ("a double > 0", "one of \"gmres\", \"cg\"").
std::string allowed_text(const Teuchos::ParameterEntry& valid);
/// The same for the documentation table (no article, Markdown code spans).
std::string allowed_markdown(const Teuchos::ParameterEntry& valid);
/// The names of a schema list's entries, comma separated.
std::string entry_names(const Teuchos::ParameterList& valid);
/// ` (did you mean "x"?)` if a name of `valid` is close to `name`, else "".
std::string suggestion(const std::string& name, const Teuchos::ParameterList& valid);
/// True if `valid` is a pass-through sublist (disableRecursiveValidation(): any content).
bool is_pass_through(const Teuchos::ParameterList& valid);
/// The number of components every value of an Array(double) entry must have (3 for vectors
/// whose default has 3), or nullopt.
std::optional<int> required_size(const Teuchos::ParameterEntry& valid);
/// Teuchos' multi-line exception text condensed to one line (the throw locations dropped).
std::string condense(const std::string& teuchos_message);

// --- validation (validate.cpp) ---

/// Checks one user value against its schema entry (type, validator, 3 components).
std::optional<Problem> check_entry(const Teuchos::ParameterEntry& user,
                                   const Teuchos::ParameterEntry& valid);
/// Checks every entry of `user` (recursively, pass-through sublists excepted) against `valid`;
/// throws InputError "<file>: parameter "<path>/<name>": ...; allowed: ...".
void check_list(const Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                const std::string& path, const std::string& file);
/// Throws InputError `<file>: parameter "<path>": <what>; allowed: <allowed>`.
[[noreturn]] void fail(const std::string& file, const std::string& path, const Problem& p);

// --- reading and overrides (xml.cpp, overrides.cpp) ---

/// Reads the XML file (Teuchos), after a strict scan of its values (numbers, bools, duplicate
/// names) that Teuchos would silently accept. Throws InputError "<file>: ...".
Teuchos::RCP<Teuchos::ParameterList> read_xml(const std::string& file);
/// The same in two parts: the file's bytes (a missing, unreadable or non-regular file refused),
/// and the XML `text` read from `file` (refused as read_xml refuses it).
std::string read_xml_text(const std::string& file);
Teuchos::RCP<Teuchos::ParameterList> parse_xml(const std::string& file, const std::string& text);
/// Parses `text` as a value of the type of `like`; throws std::invalid_argument.
Teuchos::any parse_value(const std::string& text, const Teuchos::any& like);
/// Parses a pass-through value whose type is unknown: int, double, bool, else string.
Teuchos::any guess_value(const std::string& text);
/// The path "Section/Sub/name" an override "Section/Sub/name=value" sets.
std::string override_path(const std::string& override_text);
/// Applies one "Section/Sub/name=value" override to the raw input `params` (whose sections
/// are `sections`).
void apply_override(Teuchos::ParameterList& params, const std::string& override_text,
                    const std::string& file, const std::vector<Section>& sections);

// --- documentation (docs.cpp) ---

/// A short valid input (one generated box, a Dirichlet condition), shown in the docs.
std::string example_xml();

}  // namespace emc::input::detail
