// monitors.csv: header, exact round trip, parse errors, throttled flush.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/monitors.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::has_temp_file;
using testing::slurp;
using testing::TempDir;

/// Bit-level equality (distinguishes -0.0 from 0.0).
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

/// A row whose doubles are all taken from `v` (cycling, starting at `offset`).
MonitorRow make_row(long step, const std::vector<double>& v, std::size_t offset) {
  auto at = [&](std::size_t i) { return v[(offset + i) % v.size()]; };
  MonitorRow r;
  r.step = step;
  r.time = at(0);
  r.kinetic = at(1);
  r.elastic = at(2);
  r.potential = at(3);
  r.total = at(4);
  r.L = {at(5), at(6), at(7)};
  r.J = {at(8), at(9), at(10)};
  r.active_contacts = static_cast<int>(step * 7);
  r.newton_iterations = static_cast<int>(step % 5);
  r.dt = at(11);
  r.linear_iterations = -static_cast<int>(step);
  r.com = {at(12), at(13), at(14)};
  r.gap_min = at(15);
  r.gap_max = at(16);
  r.contact_resolves = static_cast<int>(step % 3);
  r.normal_force_min = at(17);
  return r;
}

/// Every double field of a row, in column order.
std::vector<double> doubles_of(const MonitorRow& r) {
  return {r.time,      r.kinetic, r.elastic, r.potential, r.total,   r.L[0],
          r.L[1],      r.L[2],    r.J[0],    r.J[1],      r.J[2],    r.dt,
          r.com[0],    r.com[1],  r.com[2],  r.gap_min,   r.gap_max, r.normal_force_min,
          r.dissipated};
}

TEST(Monitors, HeaderIsExact) {
  EXPECT_EQ(monitor_header(),
            "step,time,kinetic,elastic,potential,total,Lx,Ly,Lz,Jx,Jy,Jz,active_contacts,"
            "newton_iterations,dt,linear_iterations,com_x,com_y,com_z,gap_min,gap_max,"
            "contact_resolves,normal_force_min,dissipated");
}

TEST(Monitors, FormatRowUsesPercent17g) {
  MonitorRow r;
  r.step = 3;
  r.time = 0.1;
  r.kinetic = -0.0;
  r.L = {1.0 / 3.0, 1e-300, 2.0};
  EXPECT_EQ(
      format_row(r),
      "3,0.10000000000000001,-0,0,0,0,0.33333333333333331,1e-300,2,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0");
  // Same text as printf("%.17g") for awkward values.
  for (double v : {0.1, 1e-300, -0.0, 1.0 / 3.0, 5e-324, 1.7976931348623157e308, 1e16, 123.5,
                   -2.5e-7, 1e21, 0.0001, std::numeric_limits<double>::infinity()}) {
    r.time = v;
    char expected[64];
    std::snprintf(expected, sizeof(expected), "%.17g", v);
    const std::string row = format_row(r);
    EXPECT_EQ(row.substr(2, row.find(',', 2) - 2), expected);
  }
}

TEST(Monitors, RoundTripIsBitIdentical) {
  const std::vector<double> awkward = {0.1,
                                       1e-300,
                                       -0.0,
                                       1.0 / 3.0,
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::max(),
                                       -std::numeric_limits<double>::min(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       123456789.0123456789,
                                       -2.5e17,
                                       std::nextafter(1.0, 2.0),
                                       0.0};
  TempDir dir;
  const std::string path = dir / "monitors.csv";
  MonitorWriter w(path);
  std::vector<MonitorRow> rows;
  for (long s = 0; s < 26; ++s) rows.push_back(make_row(s, awkward, static_cast<std::size_t>(s)));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    w.append(rows[i]);
    if (i % 7 == 0) w.flush();  // the first write replaces the file, the later ones append
  }
  w.flush();
  EXPECT_FALSE(has_temp_file(dir.path()));
  const std::vector<MonitorRow> back = read_monitors(path);
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(w.rows(), static_cast<long>(rows.size()));
  for (std::size_t i = 0; i < back.size(); ++i) {
    const MonitorRow& a = rows[i];
    const MonitorRow& b = back[i];
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.active_contacts, b.active_contacts);
    EXPECT_EQ(a.newton_iterations, b.newton_iterations);
    EXPECT_EQ(a.linear_iterations, b.linear_iterations);
    EXPECT_EQ(a.contact_resolves, b.contact_resolves);
    const std::vector<double> da = doubles_of(a), db = doubles_of(b);
    for (std::size_t k = 0; k < da.size(); ++k) {
      EXPECT_TRUE(same_bits(da[k], db[k]))
          << "row " << i << " col " << k << ": " << da[k] << " vs " << db[k];
    }
  }
}

TEST(Monitors, NanReadsBackAsNan) {
  TempDir dir;
  MonitorWriter w(dir / "m.csv");
  MonitorRow r;
  r.total = std::numeric_limits<double>::quiet_NaN();
  w.append(r);
  w.flush();
  EXPECT_TRUE(std::isnan(read_monitors(dir / "m.csv").at(0).total));
}

TEST(Monitors, FileStartsWithHeader) {
  TempDir dir;
  MonitorWriter w(dir / "m.csv");
  w.flush();
  EXPECT_EQ(slurp(dir / "m.csv"), monitor_header() + "\n");
  EXPECT_TRUE(read_monitors(dir / "m.csv").empty());
}

TEST(Monitors, ExtraColumnsAreTolerated) {
  TempDir dir;
  MonitorRow r;
  r.step = 9;
  r.time = 0.5;
  atomic_write(dir / "m.csv", monitor_header() + ",extra\n" + format_row(r) + ",42\n");
  const auto rows = read_monitors(dir / "m.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].step, 9);
  EXPECT_EQ(rows[0].time, 0.5);
}

/// read_monitors must throw an emc::Error whose text contains every string in `needles`.
void expect_read_error(const std::string& path, const std::vector<std::string>& needles) {
  try {
    read_monitors(path);
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    for (const std::string& n : needles) {
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
    }
  }
}

TEST(Monitors, BadRowNamesFileAndLine) {
  TempDir dir;
  const std::string path = dir / "m.csv";
  MonitorRow r;
  const std::string good = format_row(r) + "\n";
  atomic_write(path, monitor_header() + "\n" + good + "1,2,3\n");
  expect_read_error(path, {path + ":3:", "fields"});
  std::string bad = format_row(r);
  bad.replace(bad.find(",0,"), 3, ",zz,");  // a non-number
  atomic_write(path, monitor_header() + "\n" + good + good + bad + "\n");
  expect_read_error(path, {path + ":4:", "zz"});
  atomic_write(path, "step,time\n");
  expect_read_error(path, {path + ":1:"});
  expect_read_error(dir / "missing.csv", {dir / "missing.csv"});
}

TEST(Monitors, ThrottledFlushDoesNotRewriteBetweenForcedFlushes) {
  TempDir dir;
  const std::string path = dir / "monitors.csv";
  MonitorWriter w(path);
  w.append(make_row(0, {1.0}, 0));
  w.flush(true);
  const std::string first = slurp(path);
  ASSERT_EQ(read_monitors(path).size(), 1u);
  for (long s = 1; s <= 5; ++s) {
    w.append(make_row(s, {2.0}, 0));
    w.flush(false, 1e9);
    EXPECT_EQ(slurp(path), first) << "rewritten at step " << s;
  }
  w.flush(true);
  EXPECT_EQ(read_monitors(path).size(), 6u);
  w.append(make_row(6, {3.0}, 0));
  w.flush(false, 0.0);  // time is up: written
  EXPECT_EQ(read_monitors(path).size(), 7u);
  EXPECT_FALSE(has_temp_file(dir.path()));
}

TEST(Monitors, FirstThrottledFlushWrites) {
  TempDir dir;
  MonitorWriter w(dir / "m.csv");
  w.append(MonitorRow{});
  w.flush(false, 1e9);
  EXPECT_EQ(read_monitors(dir / "m.csv").size(), 1u);
}

TEST(Monitors, WriterIntoMissingDirectoryThrowsNamingIt) {
  TempDir dir;
  const std::string missing = dir / "nope";
  try {
    MonitorWriter w(missing + "/monitors.csv");  // the directory is opened here
    w.flush();
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

TEST(Monitors, LaterFlushesAppendToTheFileTheFirstOneReplaced) {
  TempDir dir;
  const std::string path = dir / "monitors.csv";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");  // an earlier run's longer file
    ASSERT_NE(f, nullptr);
    std::fputs((monitor_header() + "\n" + std::string(5000, 'x') + "\n").c_str(), f);
    std::fclose(f);
  }
  MonitorWriter w(path);
  w.append(make_row(0, {1.0}, 0));
  w.flush(true);
  const std::string first = slurp(path);
  struct stat before {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  for (long s = 1; s <= 40; ++s) {
    w.append(make_row(s, {2.0}, 0));
    w.flush(s % 2 == 0, 0.0);
  }
  struct stat after {};
  ASSERT_EQ(::stat(path.c_str(), &after), 0);
  EXPECT_EQ(before.st_ino, after.st_ino) << "the file was replaced, not appended to";
  const std::string all = slurp(path);
  EXPECT_EQ(all.compare(0, first.size(), first), 0) << "the first write's text changed";
  const auto back = read_monitors(path);
  ASSERT_EQ(back.size(), 41u);
  for (long s = 0; s <= 40; ++s) EXPECT_EQ(back[s].step, s);
  EXPECT_FALSE(has_temp_file(dir.path()));
}

}  // namespace
}  // namespace emc::output
