// Fuzz test of the input readers with a corpus of mutated files (docs/developer-guide.md):
//
//   fuzz_readers xml|msh|set COUNT SEED WORKDIR SEED_FILE...
//
// Each of COUNT mutants of the seed files (tests/fuzz/mutator.hpp, deterministic in SEED) is
// written to WORKDIR/current.<kind> and read by the real reader:
//   xml  emc::app::read_input (Teuchos XML, schema validation, cross-checks);
//   msh  emc::mesh::read_msh (our strict parser), then the checks and derived data every run uses
//        (boundary triangles, surface nodes);
//   set  emc::app::read_input with a mutated --set override of the first seed file.
// A mutant must either be accepted or be refused with emc::InputError whose message names the
// file; any other exception is a failure (the mutant is kept as WORKDIR/failure-N.<kind>), and a
// crash, or a hang (ctest's TIMEOUT), fails the ctest (current.<kind> is then the reproducer).
// Prints a summary.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "emcontact/app/input_schema.hpp"
#include "emcontact/error.hpp"
#include "emcontact/mesh/body_mesh.hpp"
#include "emcontact/mesh/generate.hpp"
#include "fuzz/mutator.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

/// Reads one mutant with the reader of `kind`; returns true if accepted.
bool read_one(const std::string& kind, const std::string& file, const std::string& set_text) {
  if (kind == "xml") {
    emc::app::read_input(file, {});
    return true;
  }
  if (kind == "set") {
    emc::app::read_input(file, {set_text});
    return true;
  }
  const emc::mesh::BodyMesh m = emc::mesh::read_msh(file, "", "fuzz");
  if (!emc::mesh::is_rigid(m)) {
    emc::mesh::check_tets(m, "fuzz");
    (void)emc::mesh::boundary_triangles(m);
  }
  (void)emc::mesh::surface_nodes(m, "boundary", "fuzz");
  return true;
}

/// The first words of an error message, without the file name (for the summary).
std::string category(const std::string& what, const std::string& file) {
  std::string s = what;
  for (std::size_t at; (at = s.find(file)) != std::string::npos;) s.erase(at, file.size());
  std::string out;
  int words = 0;
  for (std::size_t i = 0; i < s.size() && words < 7; ++i) {
    if (s[i] == '\n') break;
    if (s[i] == ' ') ++words;
    out += s[i];
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::cerr << "usage: fuzz_readers xml|msh|set COUNT SEED WORKDIR SEED_FILE...\n";
    return 2;
  }
  const std::string kind = argv[1];
  const long count = std::stol(argv[2]);
  const std::uint64_t seed = std::stoull(argv[3]);
  const std::string workdir = argv[4];
  std::vector<std::string> seeds;
  for (int i = 5; i < argc; ++i) seeds.push_back(slurp(argv[i]));
  std::filesystem::create_directories(workdir);
  const std::string ext = kind == "msh" ? ".msh" : ".xml";
  const std::string file = workdir + "/current" + ext;

  emc::fuzz::Mutator mutator(seed);
  long accepted = 0, refused = 0, failures = 0;
  std::map<std::string, long> reasons;
  for (long n = 0; n < count; ++n) {
    const std::size_t s = static_cast<std::size_t>(n) % seeds.size();
    std::string text = seeds[s], set_text;
    if (kind == "set") {
      const std::string base = "Time/dt=1e-3";
      set_text = mutator.mutate(n % 2 ? base : "Bodies/block/Material/density=7850");
    } else {
      text = mutator.mutate(text);
    }
    spit(file, text);
    try {
      accepted += read_one(kind, file, set_text) ? 1 : 0;
    } catch (const emc::InputError& e) {
      ++refused;
      const std::string what = e.what();
      if (kind != "set" && what.find(file) == std::string::npos &&
          what.find("current") == std::string::npos) {
        ++failures;
        std::cerr << "mutant " << n << ": the error does not name the file: " << what << "\n";
        spit(workdir + "/failure-" + std::to_string(n) + ext, text);
      }
      ++reasons[category(what, file)];
    } catch (const std::exception& e) {
      ++failures;
      std::cerr << "mutant " << n << ": unexpected " << typeid(e).name() << ": " << e.what()
                << "\n";
      spit(workdir + "/failure-" + std::to_string(n) + ext, text);
    }
  }
  std::vector<std::pair<long, std::string>> top;
  for (const auto& r : reasons) top.emplace_back(r.second, r.first);
  std::sort(top.rbegin(), top.rend());
  std::cout << "fuzz " << kind << ": " << count << " mutants of " << seeds.size()
            << " seed files (seed " << seed << "): " << accepted << " accepted, " << refused
            << " refused with emc::InputError, " << failures
            << " failures\nmost frequent refusals:\n";
  for (std::size_t i = 0; i < std::min<std::size_t>(8, top.size()); ++i)
    std::cout << "  " << top[i].first << "  " << top[i].second << "\n";
  if (failures == 0) std::filesystem::remove(file);
  return failures == 0 ? 0 : 1;
}
