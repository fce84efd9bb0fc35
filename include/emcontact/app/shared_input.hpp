#pragma once
// Every rank runs rank 0's input: its command line and its copy of the input file, broadcast
// (per-node copies of a file can differ, and an MPMD launch can give each rank other
// arguments; ranks that read different inputs hung or aborted in a collective).
#include <string>
#include <vector>

#include "emcontact/input/input.hpp"
#include "emcontact/types.hpp"

namespace emc::app {

/// Rank 0's arguments (argv[1..argc-1]) on every rank (collective). Rank 0 warns in one line
/// when another rank was started with other arguments.
std::vector<std::string> rank0_arguments(int argc, char** argv, const Comm& comm);

/// read_input (emcontact/app/input_schema.hpp) of rank 0's copy of `file` on every rank
/// (collective): rank 0 reads the file, every rank parses and validates the same text.
input::Input read_shared_input(const std::string& file, const std::vector<std::string>& overrides,
                               const Comm& comm);

}  // namespace emc::app
