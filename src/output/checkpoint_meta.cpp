// What makes a checkpoint trustworthy: the fingerprint of the model it was written for and a
// checksum of everything stored (a flipped byte or a foreign model is refused on restart).
#include "checkpoint_meta.hpp"

#include <cstring>

#include "emcontact/error.hpp"

namespace emc::output::detail {
namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull, kFnvPrime = 1099511628211ull;

void fnv(std::uint64_t& h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * kFnvPrime;
}

/// Whether the attribute holds one value (a scalar dataspace), as written: H5Aread fills as
/// many values as its dataspace has.
bool is_single_value(hid_t attr) {
  const hid_t space = H5Aget_space(attr);
  if (space < 0) return false;
  const bool one = H5Sget_simple_extent_type(space) == H5S_SCALAR;
  H5Sclose(space);
  return one;
}

void fnv(std::uint64_t& h, const std::vector<double>& v) {
  const std::uint64_t n = v.size();  // the length too: a moved boundary changes the sum
  fnv(h, &n, sizeof n);
  if (!v.empty()) fnv(h, v.data(), v.size() * sizeof(double));
}

}  // namespace

std::uint64_t checksum_head(const Checkpoint& c) {
  std::uint64_t h = kFnvOffset;
  fnv(h, c.scalars());
  return h;
}

void fnv_bytes(std::uint64_t& h, const void* data, std::size_t bytes) {
  fnv(h, data, bytes);
}

void fnv_length(std::uint64_t& h, std::uint64_t n) {
  fnv(h, &n, sizeof n);
}

void checksum_tail(std::uint64_t& h, const Checkpoint& c) {
  for (const auto* v : {&c.active, &c.normal_force}) fnv(h, *v);
  // the entries' states only when there are some: a checkpoint written before them keeps its
  // sum, and one whose states were removed does not match its own
  if (!c.state.empty()) fnv(h, c.state);
  fnv(h, c.model.data(), c.model.size());
}

std::uint64_t checksum(const Checkpoint& c) {
  std::uint64_t h = checksum_head(c);
  for (const auto* v : {&c.u, &c.V, &c.last_increment}) fnv(h, *v);
  checksum_tail(h, c);
  return h;
}

void write_string_attribute(hid_t file, const char* name, const std::string& s,
                            const std::string& path) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, s.empty() ? 1 : s.size());
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(file, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  const std::string padded = s.empty() ? std::string(1, '\0') : s;
  const herr_t st = attr < 0 ? -1 : H5Awrite(attr, type, padded.data());
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  if (st < 0) throw Error(path + ": cannot write the checkpoint attribute " + name);
}

void write_u64_attribute(hid_t file, const char* name, std::uint64_t v, const std::string& path) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(file, name, H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  const herr_t st = attr < 0 ? -1 : H5Awrite(attr, H5T_NATIVE_UINT64, &v);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  if (st < 0) throw Error(path + ": cannot write the checkpoint attribute " + name);
}

std::optional<std::string> read_string_attribute(hid_t file, const char* name,
                                                 const std::string& path) {
  if (H5Aexists(file, name) <= 0) return std::nullopt;
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  if (attr < 0) throw Error(path + ": cannot read the checkpoint attribute " + name);
  const hid_t type = H5Aget_type(attr);
  const bool ok = type >= 0 && H5Tget_class(type) == H5T_STRING && !H5Tis_variable_str(type) &&
                  is_single_value(attr);
  const std::size_t n = ok ? H5Tget_size(type) : 0;
  hsize_t bytes = 0;  // a corrupt size must not allocate more than the file can hold
  const bool fits = H5Fget_filesize(file, &bytes) >= 0 && n <= bytes;
  std::string s(fits ? n : 0, '\0');
  herr_t st = -1;
  if (ok && fits && n > 0) {
    const hid_t mem = H5Tcopy(H5T_C_S1);
    H5Tset_size(mem, n);
    st = H5Aread(attr, mem, s.data());
    H5Tclose(mem);
  }
  if (type >= 0) H5Tclose(type);
  H5Aclose(attr);
  if (!ok) throw Error(path + ": the checkpoint attribute " + name + " is not one string");
  if (st < 0) throw Error(path + ": cannot read the checkpoint attribute " + name);
  s.resize(std::strlen(s.c_str()));
  return s;
}

std::optional<std::uint64_t> read_u64_attribute(hid_t file, const char* name,
                                                const std::string& path) {
  if (H5Aexists(file, name) <= 0) return std::nullopt;
  const hid_t attr = H5Aopen(file, name, H5P_DEFAULT);
  if (attr < 0) throw Error(path + ": cannot read the checkpoint attribute " + name);
  const hid_t type = H5Aget_type(attr);
  const bool ok = type >= 0 && H5Tget_class(type) == H5T_INTEGER && H5Tget_size(type) == 8 &&
                  is_single_value(attr);
  std::uint64_t v = 0;
  const herr_t st = ok ? H5Aread(attr, H5T_NATIVE_UINT64, &v) : -1;
  if (type >= 0) H5Tclose(type);
  H5Aclose(attr);
  if (!ok) throw Error(path + ": the checkpoint attribute " + name + " is not one 64-bit integer");
  if (st < 0) throw Error(path + ": cannot read the checkpoint attribute " + name);
  return v;
}

}  // namespace emc::output::detail
