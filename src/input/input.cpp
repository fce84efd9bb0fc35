// read_input: read the XML, apply overrides, validate every section, fill defaults, cross-check.
#include "emcontact/input/input.hpp"

#include <filesystem>

#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"

namespace emc::input {
namespace {

using detail::Problem;
using detail::Section;
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
void check_sections(const ParameterList& params, const std::string& file) {
  const auto schema = valid_parameters();
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

void check_bodies(const ParameterList& params, const std::string& file) {
  if (params.sublist("Bodies").numParams() == 0)
    detail::fail(file, "Bodies", {"no body given", "one sublist per body (at least one)"});
}

void check_end_time(const ParameterList& params, const std::string& file) {
  const auto& time = params.sublist("Time");
  const double dt = time.get<double>("dt"), end = time.get<double>("end");
  if (end < dt)
    detail::fail(file, "Time/end",
                 {"end = " + detail::format_double(end) +
                      " is smaller than dt = " + detail::format_double(dt),
                  "a double >= dt"});
}

/// Each Dirichlet condition names an existing body and a (non-empty) surface.
void check_dirichlet(const ParameterList& params, const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  const auto& dirichlet = params.sublist("Dirichlet");
  for (auto it = dirichlet.begin(); it != dirichlet.end(); ++it) {
    const std::string path = "Dirichlet/" + dirichlet.name(it);
    const auto& c = dirichlet.sublist(dirichlet.name(it));
    const auto& body = c.get<std::string>("body");
    if (!bodies.isSublist(body))
      detail::fail(file, path + "/body",
                   {body.empty() ? "missing (required)" : "\"" + body + "\" is not a body",
                    "the name of a body: " + detail::entry_names(bodies)});
    if (c.get<std::string>("surface").empty())
      detail::fail(file, path + "/surface",
                   {"missing (required)", "a named surface of the mesh of body \"" + body + "\""});
  }
}

std::string directory_of(const std::string& file) {
  const std::string dir = std::filesystem::path(file).parent_path().string();
  return dir.empty() ? "." : dir;
}

}  // namespace

Input read_input(const std::string& file, const std::vector<std::string>& overrides) {
  auto params = detail::read_xml(file);
  for (const auto& o : overrides) detail::apply_override(*params, o, file);
  check_sections(*params, file);
  for (const auto& s : detail::sections()) {
    auto& section = params->sublist(s.name);
    if (s.named()) {
      validate_named(section, s, file);
    } else {
      validate_and_fill(section, *s.schema, s.name, file);
    }
  }
  check_bodies(*params, file);
  check_end_time(*params, file);
  check_dirichlet(*params, file);
  return Input{params, file, directory_of(file)};
}

}  // namespace emc::input
