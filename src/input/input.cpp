// read_input: read the XML, apply overrides, validate every section, fill defaults, cross-check
// (bodies of the Dirichlet conditions and contact pairs, rigid surface bodies at rest).
#include "emcontact/input/input.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/mesh/generate.hpp"

namespace emc::input {
namespace {

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

/// A run of at most this many nominal steps: a dt below end / kMaxSteps cannot be meant (and
/// from about end * 1e-16 on, t + dt == t: time would not advance).
constexpr double kMaxSteps = 1e9;

void check_end_time(const ParameterList& params, const std::string& file) {
  const auto& time = params.sublist("Time");
  const double dt = time.get<double>("dt"), end = time.get<double>("end");
  for (const char* name : {"dt", "end"})
    if (!std::isfinite(time.get<double>(name)))
      detail::fail(file, std::string("Time/") + name, {"is not finite", "a finite double > 0"});
  if (end / dt > kMaxSteps)
    detail::fail(file, "Time/dt",
                 {"dt = " + detail::format_double(dt) + " would take " +
                      detail::format_double(std::ceil(end / dt)) +
                      " steps to Time/end = " + detail::format_double(end),
                  "a dt >= end / 1e9 (at most 1e9 steps)"});
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

/// The `Mesh/type` of a (validated) body.
const std::string& mesh_type(const ParameterList& bodies, const std::string& body) {
  return bodies.sublist(body).sublist("Mesh").get<std::string>("type");
}

/// The bodies (of `bodies`) for which `keep(name)` holds, comma separated, or `none`.
template <class F>
std::string body_names(const ParameterList& bodies, const std::string& none, F keep) {
  std::string names;
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    if (keep(bodies.name(it))) names += (names.empty() ? "" : ", ") + bodies.name(it);
  }
  return names.empty() ? none : names;
}

/// A rigid surface body (Mesh type `plane`, `rectangle`) does not move: its `Initial`
/// velocity and angular velocity must be zero. (A `file` without tets is only known to be
/// rigid once read: the mesh side checks it.)
void check_rigid_bodies(const ParameterList& params, const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  for (auto it = bodies.begin(); it != bodies.end(); ++it) {
    const std::string& body = bodies.name(it);
    const std::string& type = mesh_type(bodies, body);
    if (!emc::mesh::is_rigid_surface_type(type)) continue;
    const auto& initial = bodies.sublist(body).sublist("Initial");
    for (const char* name : {"velocity", "angular velocity"}) {
      const auto& v = initial.get<Teuchos::Array<double>>(name);
      if (std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0; })) continue;
      detail::fail(file, "Bodies/" + body + "/Initial/" + name,
                   {"value " + detail::format_value(Teuchos::any(v)) +
                        " on a rigid surface body (Mesh type \"" + type +
                        "\"): the motion of rigid surfaces is fixed for now, they do not move",
                    "{0, 0, 0} (or leave it out)"});
    }
  }
}

/// Checks `Contact/<pair>/<role>` ("body" or "body/surface" naming an existing body); returns
/// the body name.
std::string contact_body(const ParameterList& bodies, const ParameterList& pair,
                         const std::string& role, const std::string& path,
                         const std::string& file) {
  const std::string& ref = pair.get<std::string>(role);
  const auto slash = ref.find('/');
  std::string body = ref.substr(0, slash);
  const std::string allowed =
      "a body name or body/surface (a named surface of that body); bodies: " +
      detail::entry_names(bodies);
  if (ref.empty()) detail::fail(file, path, {"missing (required)", allowed});
  if (!bodies.isSublist(body))
    detail::fail(file, path,
                 {"\"" + body + "\"" + (slash == std::string::npos ? "" : " (in \"" + ref + "\")") +
                      " is not a body",
                  allowed});
  if (slash + 1 == ref.size())
    detail::fail(file, path, {"no surface name after \"" + body + "/\"", allowed});
  return body;
}

/// Each contact pair names existing bodies, a deformable slave and a master on another body.
/// (That a `/surface` exists is checked once the meshes are built.)
void check_contact(const ParameterList& params, const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  const auto& contact = params.sublist("Contact");
  for (auto it = contact.begin(); it != contact.end(); ++it) {
    const std::string path = "Contact/" + contact.name(it);
    const auto& pair = contact.sublist(contact.name(it));
    const std::string slave = contact_body(bodies, pair, "slave", path + "/slave", file);
    const std::string master = contact_body(bodies, pair, "master", path + "/master", file);
    const std::string& type = mesh_type(bodies, slave);
    if (emc::mesh::is_rigid_surface_type(type))
      detail::fail(file, path + "/slave",
                   {"body \"" + slave + "\" is a rigid surface (Mesh type \"" + type +
                        "\"); the slave must be a deformable body (a rigid surface is always "
                        "the master)",
                    "a deformable body: " +
                        body_names(bodies, "(none in the input)", [&](const std::string& b) {
                          return !emc::mesh::is_rigid_surface_type(mesh_type(bodies, b));
                        })});
    if (master == slave)
      detail::fail(file, path + "/master",
                   {"\"" + master + "\" is also the slave's body; self-contact is not supported",
                    "a body other than \"" + slave + "\": " +
                        body_names(bodies, "(no other body in the input)",
                                   [&](const std::string& b) { return b != slave; })});
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
  check_rigid_bodies(*params, file);
  check_contact(*params, file);
  return Input{params, file, directory_of(file)};
}

}  // namespace emc::input
