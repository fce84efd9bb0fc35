// read_input: read the XML, apply overrides, validate every section of the schema, fill
// defaults, run the schema's checks across parameters.
#include "emcontact/input/input.hpp"

#include <filesystem>

#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"

namespace emc::input {
namespace {

using Teuchos::ParameterList;

/// Friendly checks first (check_list), then Teuchos validates and fills in the defaults.
void validate_and_fill(ParameterList& user, const ParameterList& schema, const std::string& path,
                       const std::string& file) {
  detail::check_list(user, schema, path, file);
  try {
    user.validateParametersAndSetDefaults(schema);
  } catch (const std::exception& e) {
    detail::fail(file, path, {detail::condense(e.what()), "see inputs/README.md"});
  }
}

/// Every top-level entry must be a known section, given as a sublist.
void check_sections(const ParameterList& params, const Schema& all, const std::string& file) {
  const auto schema = valid_parameters(all);
  for (auto it = params.begin(); it != params.end(); ++it) {
    const std::string& name = params.name(it);
    if (!schema->isSublist(name))
      detail::fail(
          file, name,
          {"unknown section" + detail::suggestion(name, *schema), detail::entry_names(*schema)});
    if (!params.entry(it).isList())
      detail::fail(file, name, {"must be a sublist, not a parameter", "a sublist"});
  }
}

/// Each entry of a named section (`Bodies/<body>`) is a sublist validated against the template.
void validate_named(ParameterList& section, const Section& s, const std::string& file) {
  const std::string what = s.placeholder.substr(1, s.placeholder.size() - 2);
  for (auto it = section.begin(); it != section.end(); ++it) {
    const std::string path = s.name + "/" + section.name(it);
    if (!section.entry(it).isList())
      detail::fail(file, path,
                   {"must be a sublist (one per " + what + "), not a parameter",
                    "a sublist with: " + detail::entry_names(*s.schema)});
    validate_and_fill(section.sublist(section.name(it)), *s.schema, path, file);
  }
}

std::string directory_of(const std::string& file) {
  const std::string dir = std::filesystem::path(file).parent_path().string();
  return dir.empty() ? "." : dir;
}

}  // namespace

bool Given::overridden(const std::string& path) const {
  for (const auto& p : override_paths)
    if (p == path || (p.size() > path.size() && p.compare(0, path.size() + 1, path + "/") == 0))
      return true;
  return false;
}

Teuchos::RCP<const ParameterList> valid_parameters(const Schema& schema) {
  auto all = Teuchos::rcp(new ParameterList("emcontact"));
  for (const auto& s : schema.sections) {
    auto& list = all->sublist(s.name, false, s.doc);
    if (s.named()) {
      list.sublist(s.placeholder) = *s.schema;
    } else {
      list = *s.schema;
    }
    list.setName(s.name);
  }
  return all;
}

std::string read_input_file(const std::string& file) {
  return detail::read_xml_text(file);
}

Input read_input(const std::string& file, const std::vector<std::string>& overrides,
                 const Schema& schema) {
  return read_input_text(file, read_input_file(file), overrides, schema);
}

Input read_input_text(const std::string& file, const std::string& text,
                      const std::vector<std::string>& overrides, const Schema& schema) {
  auto params = detail::parse_xml(file, text);
  const Teuchos::ParameterList in_file = *params;
  Given given{in_file, {}};
  for (const auto& o : overrides) {
    detail::apply_override(*params, o, file, schema.sections);
    given.override_paths.push_back(detail::override_path(o));
  }
  check_sections(*params, schema, file);
  for (const auto& s : schema.sections) {
    auto& section = params->sublist(s.name);
    if (s.named()) {
      validate_named(section, s, file);
    } else {
      validate_and_fill(section, *s.schema, s.name, file);
    }
  }
  if (schema.check) schema.check(*params, given, file);
  return Input{params, file, directory_of(file)};
}

}  // namespace emc::input
