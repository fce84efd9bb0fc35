#pragma once
// Everything a run holds, built in data-flow order: input -> meshes -> model ->
// discretization -> contact, elimination, solvers -> state and stepper. Tests use it to step a
// case and look inside (Newton's residuals, the active set).
#include <memory>

#include "emcontact/app/run.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/time/stepper.hpp"

namespace emc::app {

struct Simulation {
  input::Input in;
  fem::Model model;
  std::unique_ptr<fem::Discretization> disc;
  std::unique_ptr<contact::Contact> contact;
  std::unique_ptr<linalg::Elimination> elim;
  std::unique_ptr<linalg::LinearSolver> solver;
  std::unique_ptr<time::Newton> newton;
  time::State state;
  std::unique_ptr<time::Stepper> stepper;
};

/// Builds the simulation of `opt` (throws InputError before any work on bad input).
std::unique_ptr<Simulation> setup(const Options& opt, Teuchos::RCP<const Comm> comm);

/// The monitors.csv row of state `s` after the step `rep` reports (collective: the energies and
/// momenta are sums over the ranks).
output::MonitorRow monitor_row(const fem::Discretization& disc, const time::State& s,
                               const time::StepReport& rep);

}  // namespace emc::app
