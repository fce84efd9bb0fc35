#include "emcontact/time/interrupt.hpp"

#include <Teuchos_CommHelpers.hpp>

namespace emc::time {

volatile std::sig_atomic_t& stop_flag() {
  static volatile std::sig_atomic_t flag = 0;
  return flag;
}

bool stop_requested(const Comm& comm) {
  int mine = stop_flag() ? 1 : 0, any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine, &any);
  return any != 0;
}

}  // namespace emc::time
