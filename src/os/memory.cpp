#include "emcontact/os/memory.hpp"

#include <sys/resource.h>

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"

namespace emc::os {
namespace {

/// The model noted by note_model_size, for out_of_memory_message.
struct NotedModel {
  long long tets = -1, nodes = -1;
  int ranks = 1;
  double available = -1;  ///< bytes this process could still get when the model was noted
} g_model;

/// The value in kB of the line `key:` of a /proc file, in bytes; -1 if absent.
double proc_bytes(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream v(line.substr(key.size() + 1));
    double kb = -1;
    v >> kb;
    return kb < 0 ? -1 : kb * 1024.0;
  }
  return -1;
}

/// What this process can still allocate, and where that bound comes from.
struct Available {
  double bytes;        ///< infinity if nothing is known
  std::string source;  ///< "MemAvailable in /proc/meminfo ...", "the address space limit ..."
};

/// Resident memory: /proc/meminfo's MemAvailable shared by the `ranks_on_node` ranks of this
/// machine. Mapped (`mapped`): RLIMIT_AS less this process's mapped size (VmSize).
Available available(int ranks_on_node, bool mapped) {
  const double unknown = std::numeric_limits<double>::infinity();
  if (!mapped) {
    const double free = proc_bytes("/proc/meminfo", "MemAvailable");
    if (free < 0) return {unknown, ""};
    return {free / std::max(ranks_on_node, 1), "MemAvailable in /proc/meminfo, shared by " +
                                                   std::to_string(ranks_on_node) +
                                                   " rank(s) on this machine"};
  }
  rlimit lim{};
  if (getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return {unknown, ""};
  const double used = std::max(0.0, proc_bytes("/proc/self/status", "VmSize"));
  return {std::max(0.0, double(lim.rlim_cur) - used),
          "the address space limit, ulimit -v, less what is mapped"};
}

std::string gib(double bytes) {
  return format("%.3g GiB", bytes / 1073741824.0);
}

}  // namespace

bool keep_freed_memory() {
#if defined(__GLIBC__)
  if (std::getenv("GLIBC_TUNABLES")) return false;
  // M_MMAP_MAX = 0: large blocks come from the heap too (glibc caps M_MMAP_THRESHOLD at 32 MB,
  // below the Newton matrices); M_TRIM_THRESHOLD: the freed top of the heap stays mapped
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1;
#else
  return false;
#endif
}

double bytes_needed(double tets, int ranks, bool mapped) {
  const double shared = mapped ? kMappedBytesPerTet : kResidentBytesPerTet;
  const double base = mapped ? kMappedBaseBytes : kResidentBaseBytes;
  return base + tets * (shared / std::max(ranks, 1) + kReplicatedBytesPerTet);
}

void check_memory(double tets, int ranks, int ranks_on_node, const std::string& what) {
  for (const bool mapped : {false, true}) {
    const double need = bytes_needed(tets, ranks, mapped);
    const Available a = available(ranks_on_node, mapped);
    if (need <= a.bytes) continue;
    throw InputError(what + ", which would need about " + gib(need) + " per rank (about " +
                     std::to_string(int(mapped ? kMappedBytesPerTet : kResidentBytesPerTet)) +
                     " bytes per tetrahedron, on " + std::to_string(ranks) +
                     " rank(s)), more than the " + gib(a.bytes) + " this rank can still get (" +
                     a.source +
                     "); allowed: a coarser mesh (a larger Mesh/size), more memory or more "
                     "ranks on more machines");
  }
}

void note_model_size(long long tets, long long nodes, int ranks, int ranks_on_node) {
  g_model.tets = tets;
  g_model.nodes = nodes;
  g_model.ranks = ranks;
  g_model.available =
      std::min(available(ranks_on_node, false).bytes, available(ranks_on_node, true).bytes);
}

bool is_out_of_memory(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e)) return true;
  // Kokkos 3.4 turns its allocation failure into a std::runtime_error with this text
  const std::string what = e.what();
  return what.find("failed to allocate") != std::string::npos ||
         what.find("Allocation of size") != std::string::npos ||
         what.find(": std::bad_alloc") != std::string::npos;  // one with its context
}

std::string out_of_memory_message(const std::exception& e) {
  std::string model = "before the mesh was built";
  if (g_model.tets >= 0) {
    model = "with " + std::to_string(g_model.tets) + " tets, " + std::to_string(g_model.nodes) +
            " nodes on " + std::to_string(g_model.ranks) + " rank(s), which need about " +
            gib(bytes_needed(double(g_model.tets), g_model.ranks, true)) + " per rank";
    if (std::isfinite(g_model.available))
      model += " (" + gib(g_model.available) + " were available at the start)";
  }
  // where it happened, if a caller said so ("step 1 ...: linear solver (...) failed: Kokkos
  // failed to allocate ..."), and the last checkpoint
  const std::string what = e.what();
  auto kokkos = what.find("Kokkos failed to allocate");
  if (kokkos == std::string::npos) kokkos = what.find(": std::bad_alloc");
  std::string context = kokkos != std::string::npos ? what.substr(0, kokkos) : "";
  while (!context.empty() && (context.back() == ' ' || context.back() == ':')) context.pop_back();
  if (!context.empty()) context = " (" + context + ")";
  const auto kept = what.rfind("; the last accepted step is in ");
  const std::string tail = kept != std::string::npos ? what.substr(kept) : "";
  return "out of memory" + context + ", " + model +
         "; allowed: a coarser mesh (a larger Mesh/size), more memory, or more ranks on more "
         "machines (a direct solver needs more than the iterative ones)" +
         tail;
}

double peak_resident_bytes() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return double(u.ru_maxrss) * 1024.0;  // Linux: kilobytes
}

std::string peak_memory_line(const std::vector<double>& bytes_per_rank) {
  const auto mib = [](double b) { return std::to_string(std::llround(b / 1048576.0)); };
  std::string line = "emcontact: peak resident memory per rank: ";
  if (bytes_per_rank.size() <= 8) {
    for (const double b : bytes_per_rank) line += mib(b) + " ";
    return line + "MiB (rank 0 first)";
  }
  std::vector<double> sorted = bytes_per_rank;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  return line + "min " + mib(sorted.front()) + ", median " + mib(median) + ", max " +
         mib(sorted.back()) + ", rank 0 " + mib(bytes_per_rank.front()) + " MiB (" +
         std::to_string(n) + " ranks)";
}

std::string gather_peak_memory(const Comm& comm) {
  const double mine = peak_resident_bytes();
  std::vector<double> all(comm.getRank() == 0 ? comm.getSize() : 0);
  Teuchos::gather(&mine, 1, all.data(), 1, 0, comm);
  return comm.getRank() == 0 ? peak_memory_line(all) : std::string();
}

}  // namespace emc::os
