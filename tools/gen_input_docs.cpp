// Prints inputs/README.md: a hand-written introduction, then the generated parameter tables
// (emc::input::schema_markdown()). The ctest input_docs_up_to_date compares the two.
#include <iostream>

#include "emcontact/input/input.hpp"

namespace {

const char* const kIntro = R"(# emcontact input files

<!-- Generated file: regenerate with `build/bin/gen_input_docs > inputs/README.md` after changing
a parameter (the ctest input_docs_up_to_date fails while this file is out of date). -->

An input is a Teuchos XML parameter list (`<ParameterList name="...">`, any top-level name)
with the sections below; `emcontact input.xml` runs it. Every parameter is optional except at
least one body (and `body`/`surface` of a Dirichlet condition): what is not given takes the
default. Names are case-sensitive and unknown names are refused, as are values of the wrong
type (`type="double"`, `int`, `string`, `bool`, or `Array(double)` written `{x, y, z}`) or out
of range. A parameter can be changed from the command line with
`--set Section/Sub/name=value`, e.g. `--set Time/end=0.5`,
`--set Bodies/block/Material/young=4e6` or `--set Bodies/block/Initial/velocity={1,0,0}`; the
value is read with the parameter's type. Relative mesh file names are relative to the input
file's directory. Examples: `tumbling_box.xml` (a free box: energy and momenta are conserved)
and `falling_box.xml` (the same box under gravity).

)";

}  // namespace

int main() {
  std::cout << kIntro << emc::input::schema_markdown();
  return 0;
}
