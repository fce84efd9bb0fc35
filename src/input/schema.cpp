// The whole input schema, assembled from the modules' parameter declarations.
#include "emcontact/contact/parameters.hpp"
#include "emcontact/fem/parameters.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "emcontact/mesh/generate.hpp"
#include "emcontact/output/parameters.hpp"
#include "emcontact/time/parameters.hpp"

namespace emc::input {
namespace detail {
namespace {

/// Template of one body: `Mesh` (mesh module), then `Material` and `Initial` (fem module).
Teuchos::RCP<const Teuchos::ParameterList> body_template() {
  auto body = Teuchos::rcp(new Teuchos::ParameterList("<body>"));
  auto& mesh = body->sublist("Mesh", false, "The body's mesh: a Gmsh file or a generated shape.");
  mesh = *emc::mesh::valid_mesh_parameters();
  mesh.setName("Mesh");
  const auto fem = emc::fem::valid_body_parameters();
  for (auto it = fem->begin(); it != fem->end(); ++it)
    body->setEntry(fem->name(it), fem->entry(it));
  return body;
}

/// `Solver`: `Newton` and `Linear` (linalg module), then `Assembly` (fem module).
Teuchos::RCP<const Teuchos::ParameterList> solver_schema() {
  auto solver = Teuchos::rcp(new Teuchos::ParameterList(*emc::linalg::valid_parameters()));
  auto& assembly = solver->sublist("Assembly", false, "Element assembly of each Newton iteration.");
  assembly = *emc::fem::valid_assembly_parameters();
  assembly.setName("Assembly");
  return solver;
}

}  // namespace

std::vector<Section> sections() {
  return {
      {"Time", "Time stepping.", emc::time::valid_parameters(), ""},
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

}  // namespace detail

Teuchos::RCP<const Teuchos::ParameterList> valid_parameters() {
  auto all = Teuchos::rcp(new Teuchos::ParameterList("emcontact"));
  for (const auto& s : detail::sections()) {
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

}  // namespace emc::input
