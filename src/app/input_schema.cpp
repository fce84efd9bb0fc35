// The whole input schema, assembled from the modules' parameter declarations, and the checks
// across sections (bodies of the Dirichlet conditions and contact pairs, rigid surface bodies at
// rest, the end time against dt).
#include "emcontact/app/input_schema.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <cmath>

#include "emcontact/contact/parameters.hpp"
#include "emcontact/fem/parameters.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "emcontact/mesh/generate.hpp"
#include "emcontact/output/parameters.hpp"
#include "emcontact/time/parameters.hpp"

namespace emc::app {
namespace {

namespace detail = emc::input::detail;
using Teuchos::ParameterList;

/// The sublist `name` of `list`, documented `doc`, set to `schema`.
void set_sublist(ParameterList& list, const std::string& name, const std::string& doc,
                 const ParameterList& schema) {
  auto& sub = list.sublist(name, false, doc);
  sub = schema;
  sub.setName(name);
}

/// Every entry of `from`, appended to `to` in order.
void append_entries(ParameterList& to, const ParameterList& from) {
  for (auto it = from.begin(); it != from.end(); ++it) to.setEntry(from.name(it), from.entry(it));
}

/// Template of one body: `Mesh` (mesh module), then `Material` and `Initial` (fem module).
Teuchos::RCP<const ParameterList> body_template() {
  auto body = Teuchos::rcp(new ParameterList("<body>"));
  set_sublist(*body, "Mesh", "The body's mesh: a Gmsh file or a generated shape.",
              *emc::mesh::valid_mesh_parameters());
  append_entries(*body, *emc::fem::valid_body_parameters());
  return body;
}

/// `Time`: the time module's parameters.
Teuchos::RCP<const ParameterList> time_schema() {
  return Teuchos::rcp(new ParameterList(*emc::time::valid_parameters()));
}

/// `Solver`: `Newton` (time module), `Linear` (linalg module), then `Assembly` (fem module).
Teuchos::RCP<const ParameterList> solver_schema() {
  auto solver = Teuchos::rcp(new ParameterList("Solver"));
  set_sublist(*solver, "Newton", "Newton iteration of each time step.",
              *emc::time::valid_newton_parameters());
  set_sublist(*solver, "Linear", "Linear solver of each Newton iteration.",
              *emc::linalg::valid_linear_parameters());
  set_sublist(*solver, "Assembly", "Element assembly of each Newton iteration.",
              *emc::fem::valid_assembly_parameters());
  return solver;
}

std::vector<input::Section> sections() {
  return {
      {"Time", "Time stepping.", time_schema(), ""},
      {"Bodies",
       "One sublist per body; its name (`<body>` below) is free. At least one body is required. "
       "A body whose `Mesh` has no tetrahedra (`type` `plane` or `rectangle`, or a `file` with "
       "triangles only) is a rigid surface: it can only be the master of a contact pair, it "
       "needs no `Material`, and it does not move (its motion is fixed for now: a non-zero "
       "`Initial` velocity or angular velocity is refused).",
       body_template(), "<body>"},
      {"Loads", "External loads.", emc::fem::valid_load_parameters(), ""},
      {"Dirichlet",
       "Optional: one sublist per fixed surface; its name (`<condition>` below) is free. The "
       "displacement of the surface's nodes is fixed to zero.",
       emc::fem::valid_dirichlet_parameters(), "<condition>"},
      {"Contact",
       "Optional: one sublist per contact pair; its name (`<pair>` below) is free. The nodes of "
       "the slave surface (of a deformable body) may not penetrate the facets of the master "
       "surface (of another body, deformable or rigid); see \"Choosing slave and master\" "
       "above.",
       emc::contact::valid_pair_parameters(), "<pair>"},
      {"Solver", "Newton and linear solvers, element assembly.", solver_schema(), ""},
      {"Output", "What is written and where.", emc::output::valid_parameters(), ""},
  };
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

/// Calls f(path, sublist) for each user-named sublist of the named section `section` (path
/// "<section>/<name>").
template <class F>
void for_each_named(const ParameterList& params, const std::string& section, F f) {
  const auto& list = params.sublist(section);
  for (auto it = list.begin(); it != list.end(); ++it)
    f(section + "/" + list.name(it), list.sublist(list.name(it)));
}

/// Each Dirichlet condition names an existing body and a (non-empty) surface.
void check_dirichlet(const ParameterList& params, const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  for_each_named(params, "Dirichlet", [&](const std::string& path, const ParameterList& c) {
    const auto& body = c.get<std::string>("body");
    if (!bodies.isSublist(body))
      detail::fail(file, path + "/body",
                   {body.empty() ? "missing (required)" : "\"" + body + "\" is not a body",
                    "the name of a body: " + detail::entry_names(bodies)});
    if (c.get<std::string>("surface").empty())
      detail::fail(file, path + "/surface",
                   {"missing (required)", "a named surface of the mesh of body \"" + body + "\""});
  });
}

/// The `Mesh/type` of a (validated) body, as written.
const std::string& mesh_type(const ParameterList& bodies, const std::string& body) {
  return bodies.sublist(body).sublist("Mesh").get<std::string>("type");
}

/// True when a (validated) body is a rigid surface by its `Mesh/type` (its validator's value).
bool rigid_surface(const ParameterList& bodies, const std::string& body) {
  return emc::mesh::is_rigid_surface_type(
      Teuchos::getIntegralValue<emc::mesh::MeshType>(bodies.sublist(body).sublist("Mesh"), "type"));
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
    if (!rigid_surface(bodies, body)) continue;
    const std::string& type = mesh_type(bodies, body);
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

/// The `Mesh` parameters that a body's `Mesh/type` reads, comma separated.
std::string parameters_of_type(const std::string& type) {
  std::string names = "type";
  const auto schema = emc::mesh::valid_mesh_parameters();
  for (auto it = schema->begin(); it != schema->end(); ++it) {
    const auto types = emc::mesh::types_reading(schema->name(it));
    if (std::find(types.begin(), types.end(), type) != types.end())
      names += ", " + schema->name(it);
  }
  return names;
}

/// The `Mesh/type` of body `body` in the input file itself ("box" if it gives none).
std::string type_in_file(const input::Given& given, const std::string& body) {
  const auto& bodies = given.file.sublist("Bodies");
  if (!bodies.isSublist(body) || !bodies.sublist(body).isSublist("Mesh")) return "box";
  const auto& mesh = bodies.sublist(body).sublist("Mesh");
  return mesh.isType<std::string>("type") ? mesh.get<std::string>("type") : "box";
}

/// A body's `Mesh` gives only parameters its `type` reads: a `file` with type `box`, or the
/// radii of a shell on a cylinder, would be silently ignored (entries the user did not give
/// are the schema's defaults, marked as such). A parameter of the file's own type is not
/// refused when an override changed the type (`--set Bodies/b/Mesh/type=plane` on a box).
void check_mesh_parameters(const ParameterList& params, const input::Given& given,
                           const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  for (auto b = bodies.begin(); b != bodies.end(); ++b) {
    const auto& mesh = bodies.sublist(bodies.name(b)).sublist("Mesh");
    const std::string& type = mesh.get<std::string>("type");
    const std::string path = "Bodies/" + bodies.name(b) + "/Mesh/";
    const bool retyped = given.overridden(path + "type");
    for (auto it = mesh.begin(); it != mesh.end(); ++it) {
      const std::vector<std::string> types = emc::mesh::types_reading(mesh.name(it));
      const auto reads = [&](const std::string& t) {
        return std::find(types.begin(), types.end(), t) != types.end();
      };
      if (mesh.entry(it).isDefault() || types.empty() || reads(type)) continue;
      if (retyped && !given.overridden(path + mesh.name(it)) &&
          reads(type_in_file(given, bodies.name(b))))
        continue;
      std::string readers;
      for (const auto& t : types) readers += (readers.empty() ? "\"" : ", \"") + t + "\"";
      detail::fail(file, "Bodies/" + bodies.name(b) + "/Mesh/" + mesh.name(it),
                   {"given, but type \"" + type + "\" does not read it (it is a parameter of " +
                        (types.size() == 1 ? "type " : "types ") + readers + ")",
                    "the parameters of type \"" + type + "\": " + parameters_of_type(type) +
                        "; or a type that reads it"});
    }
  }
}

/// Whether the input file or an override gives `Bodies/<body>/Material/<name>` (a Material
/// sublist the file leaves out is the schema's, whose entries are not marked as defaults).
bool material_given(const input::Given& given, const std::string& body, const std::string& name) {
  const std::string path = "Bodies/" + body + "/Material/" + name;
  if (given.overridden(path)) return true;
  const auto& bodies = given.file.sublist("Bodies");
  return bodies.isSublist(body) && bodies.sublist(body).isSublist("Material") &&
         bodies.sublist(body).sublist("Material").isParameter(name);
}

/// docs/THEORY.md §12.1: c2 is a parameter of model mooney-rivlin alone.
void check_material_parameters(const ParameterList& params, const input::Given& given,
                               const std::string& file) {
  const auto& bodies = params.sublist("Bodies");
  for (auto b = bodies.begin(); b != bodies.end(); ++b) {
    const std::string& body = bodies.name(b);
    const std::string model = bodies.sublist(body).sublist("Material").get<std::string>("model");
    if (model != "mooney-rivlin" && material_given(given, body, "c2"))
      detail::fail(file, "Bodies/" + body + "/Material/c2",
                   {"given, but model \"" + model +
                        "\" does not read it (it is a parameter of model \"mooney-rivlin\")",
                    "with model \"" + model + "\": young, poisson, density"});
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
  for_each_named(params, "Contact", [&](const std::string& path, const ParameterList& pair) {
    const std::string slave = contact_body(bodies, pair, "slave", path + "/slave", file);
    const std::string master = contact_body(bodies, pair, "master", path + "/master", file);
    if (rigid_surface(bodies, slave))
      detail::fail(
          file, path + "/slave",
          {"body \"" + slave + "\" is a rigid surface (Mesh type \"" + mesh_type(bodies, slave) +
               "\"); the slave must be a deformable body (a rigid surface is always "
               "the master)",
           "a deformable body: " +
               body_names(bodies, "(none in the input)",
                          [&](const std::string& b) { return !rigid_surface(bodies, b); })});
    if (master == slave)
      detail::fail(file, path + "/master",
                   {"\"" + master + "\" is also the slave's body; self-contact is not supported",
                    "a body other than \"" + slave + "\": " +
                        body_names(bodies, "(no other body in the input)",
                                   [&](const std::string& b) { return b != slave; })});
  });
}

/// The Belos parameters that replace emcontact's own limits must be as valid as those:
/// Belos itself accepts `Maximum Iterations = -1` (and stops after one iteration, a failed
/// solve whose message would not name it) and any `Convergence Tolerance`.
void check_belos(const ParameterList& params, const std::string& file) {
  const auto& belos = params.sublist("Solver").sublist("Linear").sublist("Belos");
  const std::string path = "Solver/Linear/Belos/";
  for (const char* name : {"Maximum Iterations", "Num Blocks"}) {
    if (!belos.isType<int>(name) || belos.get<int>(name) >= 1) continue;
    detail::fail(file, path + name,
                 {"value " + std::to_string(belos.get<int>(name)) + " is out of range",
                  "an int >= 1 (or leave it out: Solver/Linear/max iterations)"});
  }
  const char* tol = "Convergence Tolerance";  // "2" on the command line reads as an int
  const bool given = belos.isType<double>(tol) || belos.isType<int>(tol);
  const double t = belos.isType<int>(tol) ? belos.get<int>(tol)
                   : given                ? belos.get<double>(tol)
                                          : 0.5;
  if (!(t > 0 && t < 1))
    detail::fail(file, path + tol,
                 {"value " + detail::format_double(t) + " is out of range",
                  "a double > 0 and < 1 (or leave it out: Solver/Linear/tolerance)"});
}

/// The checks across sections, in this order.
void check(const ParameterList& params, const input::Given& given, const std::string& file) {
  check_bodies(params, file);
  check_end_time(params, file);
  check_dirichlet(params, file);
  check_rigid_bodies(params, file);
  check_mesh_parameters(params, given, file);
  check_material_parameters(params, given, file);
  check_contact(params, file);
  check_belos(params, file);
}

}  // namespace

input::Schema input_schema() {
  return {sections(), check};
}

input::Input read_input(const std::string& file, const std::vector<std::string>& overrides) {
  return input::read_input(file, overrides, input_schema());
}

}  // namespace emc::app
