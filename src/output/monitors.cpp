// DIR/monitors.csv: formatting, incremental atomic rewriting, and parsing back.
#include "emcontact/output/monitors.hpp"

#include <array>
#include <charconv>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/input/files.hpp"
#include "emcontact/output/atomic_file.hpp"

namespace emc::output {
namespace {

/// The fixed columns, in file order (the first 16 of any valid header).
constexpr const char* kColumns[] = {"step",
                                    "time",
                                    "kinetic",
                                    "elastic",
                                    "potential",
                                    "total",
                                    "Lx",
                                    "Ly",
                                    "Lz",
                                    "Jx",
                                    "Jy",
                                    "Jz",
                                    "active_contacts",
                                    "newton_iterations",
                                    "dt",
                                    "linear_iterations",
                                    "com_x",
                                    "com_y",
                                    "com_z",
                                    "gap_min",
                                    "gap_max",
                                    "contact_resolves",
                                    "normal_force_min"};
constexpr std::size_t kNumColumns = sizeof(kColumns) / sizeof(kColumns[0]);
/// Written after the fixed columns; files of earlier versions (golds, runs to restart) lack it
/// and read as 0 (docs/THEORY.md §11.2).
constexpr const char* kDissipated = "dissipated";

/// Appends `v` as printf("%.17g") would in the C locale (std::to_chars is specified so),
/// which round-trips every double exactly.
void append_double(std::string& out, double v) {
  std::array<char, 64> buf;
  const auto res =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  out.append(buf.data(), res.ptr);
}

/// Appends an integer in decimal.
void append_integer(std::string& out, long long v) {
  std::array<char, 32> buf;
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  out.append(buf.data(), res.ptr);
}

/// Seconds on the steady clock (never jumps back, unlike the wall clock).
double steady_seconds() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

/// Splits a CSV line on ',' (no quoting: monitors.csv holds numbers only).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

/// Parses the whole of `s` as a T (double or integer); throws std::invalid_argument otherwise.
template <typename T>
T parse_number(const std::string& s) {
  T value{};
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (first != last && *first == '+') ++first;  // from_chars refuses a leading '+'
  const auto res = std::from_chars(first, last, value);
  if (res.ec != std::errc() || res.ptr != last || first == last) {
    throw std::invalid_argument("'" + s + "' is not a valid number");
  }
  return value;
}

/// Fills a row from the first kNumColumns fields (already checked to be there).
MonitorRow parse_row(const std::vector<std::string>& f, bool dissipated) {
  MonitorRow r;
  std::size_t i = 0;
  r.step = parse_number<long>(f[i++]);
  r.time = parse_number<double>(f[i++]);
  r.kinetic = parse_number<double>(f[i++]);
  r.elastic = parse_number<double>(f[i++]);
  r.potential = parse_number<double>(f[i++]);
  r.total = parse_number<double>(f[i++]);
  for (double& x : r.L) x = parse_number<double>(f[i++]);
  for (double& x : r.J) x = parse_number<double>(f[i++]);
  r.active_contacts = parse_number<int>(f[i++]);
  r.newton_iterations = parse_number<int>(f[i++]);
  r.dt = parse_number<double>(f[i++]);
  r.linear_iterations = parse_number<int>(f[i++]);
  for (double& x : r.com) x = parse_number<double>(f[i++]);
  r.gap_min = parse_number<double>(f[i++]);
  r.gap_max = parse_number<double>(f[i++]);
  r.contact_resolves = parse_number<int>(f[i++]);
  r.normal_force_min = parse_number<double>(f[i++]);
  if (dissipated) r.dissipated = parse_number<double>(f[i++]);
  return r;
}

/// Removes a trailing '\r' (a file edited on Windows).
void chomp(std::string& line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
}

/// Checks that the header starts with the fixed columns; returns its number of columns and
/// whether the dissipated column follows them.
std::size_t check_header(const std::string& path, const std::string& line, bool& dissipated) {
  const std::vector<std::string> names = split_csv(line);
  dissipated = names.size() > kNumColumns && names[kNumColumns] == kDissipated;
  std::size_t differs = 0;  // the first column that is not the monitors', 1-based
  for (std::size_t i = 0; differs == 0 && i < kNumColumns; ++i)
    if (i >= names.size() || names[i] != kColumns[i]) differs = i + 1;
  // the file's own text is not quoted: a link may point at any file the user can read
  if (differs > 0)
    throw Error(path + ":1: not a monitors file: its header's column " + std::to_string(differs) +
                " is not '" + kColumns[differs - 1] + "' (the header starts '" +
                input::echo(monitor_header()) + "')");
  return names.size();
}

}  // namespace

std::string monitor_header() {
  std::string h;
  for (std::size_t i = 0; i < kNumColumns; ++i) {
    if (i > 0) h += ',';
    h += kColumns[i];
  }
  return h + ',' + kDissipated;
}

std::string format_row(const MonitorRow& r) {
  std::string s;
  s.reserve(400);
  append_integer(s, r.step);
  for (double v : {r.time, r.kinetic, r.elastic, r.potential, r.total, r.L[0], r.L[1], r.L[2],
                   r.J[0], r.J[1], r.J[2]}) {
    s += ',';
    append_double(s, v);
  }
  s += ',';
  append_integer(s, r.active_contacts);
  s += ',';
  append_integer(s, r.newton_iterations);
  s += ',';
  append_double(s, r.dt);
  s += ',';
  append_integer(s, r.linear_iterations);
  for (double v : {r.com[0], r.com[1], r.com[2], r.gap_min, r.gap_max}) {
    s += ',';
    append_double(s, v);
  }
  s += ',';
  append_integer(s, r.contact_resolves);
  s += ',';
  append_double(s, r.normal_force_min);
  s += ',';
  append_double(s, r.dissipated);
  return s;
}

MonitorWriter::MonitorWriter(Directory dir, std::string name)
    : dir_(std::move(dir)), name_(std::move(name)) {
  pending_ = monitor_header() + '\n';
}

MonitorWriter::MonitorWriter(const std::string& path)
    : MonitorWriter(directory_of(path), base_name(path)) {}

void MonitorWriter::append(const MonitorRow& r) {
  pending_ += format_row(r);
  pending_ += '\n';
  ++rows_;
}

void MonitorWriter::flush(bool force, double min_seconds) {
  const double now = steady_seconds();
  if (file_.is_open() && pending_.empty() && !force) return;                 // nothing new
  if (!force && file_.is_open() && now - last_write_ < min_seconds) return;  // too soon
  if (!file_.is_open()) {
    file_.replace(dir_, name_, pending_);  // the first write: the file of an earlier run goes
  } else if (!pending_.empty()) {
    file_.write_at(file_.size(), pending_);
  }
  if (force) file_.sync();
  pending_.clear();
  last_write_ = now;
}

std::vector<MonitorRow> read_monitors(const std::string& path) {
  input::check_regular_file(path, "monitors file");  // a FIFO would block the read
  std::ifstream in(path);
  if (!in) throw Error("cannot open monitors file '" + path + "'");
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ":1: empty monitors file");
  chomp(line);
  bool dissipated = false;
  const std::size_t num_columns = check_header(path, line, dissipated);
  std::vector<MonitorRow> rows;
  for (long line_no = 2; std::getline(in, line); ++line_no) {
    chomp(line);
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_csv(line);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (fields.size() != num_columns) {
      throw Error(where + "expected " + std::to_string(num_columns) + " fields, got " +
                  std::to_string(fields.size()));
    }
    try {
      rows.push_back(parse_row(fields, dissipated));
    } catch (const std::invalid_argument& e) {
      throw Error(where + e.what());
    }
  }
  if (in.bad()) throw Error("error reading monitors file '" + path + "'");
  return rows;
}

}  // namespace emc::output
