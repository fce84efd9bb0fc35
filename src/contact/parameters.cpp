// Schema of one contact pair (`Contact/<pair>`).
#include "emcontact/contact/parameters.hpp"

#include "emcontact/contact/pairs.hpp"
#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/input/validators.hpp"

namespace emc::contact {

using namespace emc::input;

Teuchos::RCP<const Teuchos::ParameterList> valid_pair_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<pair>"));
  pl->set("slave", std::string(""),
          "Required: the slave surface, whose nodes are constrained: a body name (its whole "
          "boundary) or body/surface with a named surface of that body (e.g. ball/outer). The "
          "slave body must be deformable (a rigid surface is always the master).",
          any_string());
  pl->set("master", std::string(""),
          "Required: the master surface, whose facets the slave nodes touch: a body name (the "
          "boundary of a deformable body, all triangles of a rigid surface) or body/surface. "
          "A named surface of a deformable body is completed by the rest of its body's boundary "
          "(a slave node may reach the body through another face, docs/THEORY.md §6.3). Not "
          "the slave's body (no self-contact).",
          any_string());
  pl->set("type", std::string("full stick"),
          "Contact condition on an active slave node: full stick (it sticks to its point of the "
          "master facet), frictionless (it slides freely on the master; only its normal gap "
          "is constrained) or coulomb (it sticks while the tangential force is at most the "
          "friction coefficient times the normal force, and slides otherwise against a "
          "tangential force of that size; docs/THEORY.md §11).",
          string_choice("type", {"full stick", "frictionless", "coulomb"},
                        {"an active slave node sticks to its point of the master facet",
                         "an active slave node slides freely on the master facet (only its "
                         "normal gap is constrained)",
                         "Coulomb friction: an active slave node sticks (as full stick) while "
                         "|f_T| <= mu f_N and slides (as frictionless, with the tangential force "
                         "mu f_N against its slip) otherwise"},
                        std::vector<Kind>{Kind::full_stick, Kind::frictionless, Kind::coulomb}));
  pl->set("max penetration", 0.0,
          "Largest penetration [m] at which a slave node is caught by a master facet (a node "
          "deeper than this, e.g. behind a thin master, is not activated); 0: automatic, half "
          "the mean edge length of the master's facets. A step in which a slave node crosses a "
          "master facet and ends deeper than this behind it fails and is solved again with "
          "dt/2 (docs/THEORY.md §6.3). At most the master surface's bounding-box diagonal, and "
          "at least the round-off of a gap on it (64 eps times its largest coordinate plus its "
          "mean facet edge).",
          double_at_least(0.0));
  pl->set("close gap", false,
          "true: every active slave node ends each step on its master facet (g_N = 0 at the "
          "end of the step; docs/THEORY.md §7): the gap an activated node had at the start of "
          "the step (up to |V| dt above the master) is closed, and the kinetic energy the "
          "closure takes (or gives) is restored by a velocity update along the contact "
          "normals that keeps L and J, so energy stays conserved. false: an activated node "
          "keeps its gap at activation (§6.5).");
  pl->set("massless slave", false,
          "true: the slave surface's nodes carry no mass; each moves as an affine fit over the "
          "massive nodes around it, and its mass goes onto them keeping the body's mass, centre "
          "of mass and inertia (docs/THEORY.md §6.8). A held slave node then has no inertia "
          "whose reflected velocity could pull it off the master, so nodes do not cycle between "
          "caught and released. Declare the contact face as the slave (body/surface), not a "
          "whole body: the mass matrix fills in around every massless node. For flush faces "
          "that stay pressed; it costs where a free surface rings (the paper's ball: 3.39 "
          "instead of 1.83 Newton iterations per step to its first rebound). Refused for a "
          "body without nodes off the slave surface that span 3D around a slave node, and with "
          "close gap.");
  pl->set("friction coefficient", 0.0,
          "Coulomb friction coefficient mu >= 0 of the pair (type = coulomb only; any other "
          "type refuses a nonzero value). mu = 0 slides as frictionless; a large mu sticks as "
          "full stick. The work of friction is the monitors' dissipated column.",
          double_at_least(0.0));
  return pl;
}

std::vector<PairSettings> read_pair_settings(const Teuchos::ParameterList& params,
                                             const std::string& file) {
  std::vector<PairSettings> out;
  if (!params.isSublist("Contact")) return out;
  const auto& cl = params.sublist("Contact");
  for (const std::string& name : input::sublist_names(cl)) {
    const auto& c = cl.sublist(name);
    const std::string where = file + ": Contact/" + name;
    PairSettings p;
    p.name = name;
    p.type = c.get<std::string>("type");
    p.kind = Teuchos::getIntegralValue<Kind>(c, "type");
    p.mu = c.get<double>("friction coefficient");
    if (p.mu != 0 && p.kind != Kind::coulomb)
      throw InputError(where + "/friction coefficient: " + format("%g", p.mu) +
                       " is only used with type = coulomb (type is \"" + p.type + "\")");
    p.close_gap = c.get<bool>("close gap");
    p.massless_slave = c.get<bool>("massless slave");
    if (p.massless_slave && p.close_gap)
      throw InputError(where +
                       ": massless slave = true and close gap = true cannot be combined "
                       "(the closure gives its energy back through the inverse mass matrix, "
                       "which massless nodes do not have); allowed: one of them");
    p.slave = c.get<std::string>("slave");
    p.master = c.get<std::string>("master");
    p.dmax = c.get<double>("max penetration");
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace emc::contact
