#pragma once
// The Teuchos timers of the per-step breakdown (printed at the end of a run and read by the
// perf/ reports): assembly, contact (search, projection, constraint rows, normal forces),
// elimination, linear solve. The preconditioner and output timers live in their modules.
#include <Teuchos_TimeMonitor.hpp>

namespace emc::time {

inline Teuchos::Time& assembly_timer() {
  static auto t = Teuchos::TimeMonitor::getNewTimer("emcontact: assembly");
  return *t;
}
inline Teuchos::Time& contact_timer() {
  static auto t = Teuchos::TimeMonitor::getNewTimer("emcontact: contact");
  return *t;
}
inline Teuchos::Time& elimination_timer() {
  static auto t = Teuchos::TimeMonitor::getNewTimer("emcontact: elimination");
  return *t;
}
inline Teuchos::Time& linear_solve_timer() {
  static auto t = Teuchos::TimeMonitor::getNewTimer("emcontact: linear solve");
  return *t;
}

}  // namespace emc::time
