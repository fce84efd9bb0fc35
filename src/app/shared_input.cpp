#include "emcontact/app/shared_input.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <cstdio>
#include <exception>

#include "emcontact/app/input_schema.hpp"
#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"

namespace emc::app {
namespace {

void broadcast_string(const Comm& comm, std::string& s) {
  std::vector<char> v(s.begin(), s.end());
  broadcast_vector(comm, v);
  s.assign(v.begin(), v.end());
}

}  // namespace

std::vector<std::string> rank0_arguments(int argc, char** argv, const Comm& comm) {
  std::string mine;  // the arguments, each ended by a NUL
  for (int i = 1; i < argc; ++i) (mine += argv[i]) += '\0';
  std::string all = mine;
  broadcast_string(comm, all);
  // the lowest rank whose own arguments differ, or the size: rank 0 names it
  int differs = all == mine ? comm.getSize() : comm.getRank(), first = comm.getSize();
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 1, &differs, &first);
  if (first < comm.getSize() && comm.getRank() == 0)
    std::fprintf(stderr,
                 "warning: rank %d was started with other arguments than rank 0; every rank "
                 "runs rank 0's (%d ranks)\n",
                 first, comm.getSize());
  std::vector<std::string> args;
  for (std::size_t b = 0; b < all.size();) {
    const std::size_t e = all.find('\0', b);
    args.push_back(all.substr(b, e - b));
    b = e + 1;
  }
  return args;
}

input::Input read_shared_input(const std::string& file, const std::vector<std::string>& overrides,
                               const Comm& comm) {
  std::string text, error;
  if (comm.getRank() == 0) {
    try {
      text = input::read_input_file(file);
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = file + ": cannot read the input";
    }
  }
  broadcast_string(comm, error);
  if (!error.empty()) throw InputError(error);
  broadcast_string(comm, text);
  return input::read_input_text(file, text, overrides, input_schema());
}

}  // namespace emc::app
