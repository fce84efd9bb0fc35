// The per-rank peak resident memory of emcontact's summary (src/os/memory.cpp): each rank's
// number is at least what that rank has touched, in rank order, and the line's two forms.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Tpetra_Core.hpp>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "emcontact/os/memory.hpp"

namespace {

constexpr double kMiB = 1048576.0;

/// The numbers of "emcontact: peak resident memory per rank: a b c MiB (rank 0 first)".
std::vector<double> numbers(const std::string& line) {
  const std::string head = "emcontact: peak resident memory per rank: ";
  EXPECT_EQ(line.compare(0, head.size(), head), 0) << line;
  std::istringstream in(line.substr(head.size()));
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

}  // namespace

// Rank r touches 200 + 300 r MiB before the gather: its number is at least that (an independent
// lower bound), and at most what the machine has. The bounds differ by more than a process's
// own footprint (about 100 MiB here), so that a gather in the wrong order, or of one rank's value
// for all, fails on 2 ranks.
TEST(PeakMemory, EachRankAtLeastWhatItTouched) {
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();
  const std::size_t bytes = std::size_t((200 + 300 * rank) * kMiB);
  std::vector<char> touched(bytes, 1);  // every page written
  const long sum = std::accumulate(touched.begin(), touched.end(), 0L);
  ASSERT_EQ(sum, long(bytes));
  EXPECT_GE(emc::os::peak_resident_bytes(), double(bytes));
  const std::string line = emc::os::gather_peak_memory(*comm);
  if (rank != 0) {
    EXPECT_TRUE(line.empty());
    return;
  }
  EXPECT_NE(line.find("MiB (rank 0 first)"), std::string::npos) << line;
  const auto mib = numbers(line);
  std::printf("%s\n", line.c_str());
  ASSERT_EQ(int(mib.size()), comm->getSize()) << line;
  const double machine = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / kMiB;
  for (int r = 0; r < comm->getSize(); ++r) {
    EXPECT_GE(mib[r], 200 + 300 * r) << "rank " << r << ": " << line;
    EXPECT_LE(mib[r], machine) << "rank " << r << ": " << line;
  }
}

TEST(PeakMemory, LineListsUpToEightRanks) {
  EXPECT_EQ(emc::os::peak_memory_line({466 * kMiB, 379 * kMiB, 379.4 * kMiB, 370 * kMiB}),
            "emcontact: peak resident memory per rank: 466 379 379 370 MiB (rank 0 first)");
}

TEST(PeakMemory, LineSummarisesMoreRanks) {
  std::vector<double> b;
  for (int r = 0; r < 10; ++r) b.push_back((r == 0 ? 500 : 300 + r) * kMiB);
  // sorted: 301 ... 309, 500: median (305 + 306) / 2 = 305.5, printed rounded
  EXPECT_EQ(emc::os::peak_memory_line(b),
            "emcontact: peak resident memory per rank: min 301, median 306, max 500, rank 0 500 "
            "MiB (10 ranks)");
}
