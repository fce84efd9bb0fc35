#include "emcontact/output/checkpoint.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cmath>

#include "checkpoint_meta.hpp"
#include "emcontact/error.hpp"
#include "emcontact/input/files.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/hdf5_file.hpp"

namespace emc::output {

namespace {

void write_vector(hid_t file, const char* name, const std::vector<double>& v,
                  const std::string& path) {
  const hsize_t n = v.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t set = space < 0 ? -1
                              : H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                           H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = set < 0 ? -1
                      : H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                 v.empty() ? nullptr : v.data());
  if (set >= 0 && H5Dclose(set) < 0) st = -1;
  if (space >= 0) H5Sclose(space);
  if (st < 0) throw Error(path + ": cannot write the checkpoint dataset " + name);
}

/// Closes an HDF5 id on scope exit.
struct Id {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Id() {
    if (id >= 0) close(id);
  }
};

/// The lengths a dataset may have: `ok(n)`, described as `allowed` in a refusal.
struct Length {
  std::function<bool(std::size_t)> ok;
  std::string allowed;
};

[[noreturn]] void refuse_dataset(const std::string& path, const char* name,
                                 const std::string& what) {
  throw Error(path + ": the checkpoint dataset " + name + " " + what);
}

/// Values [first, first + count) of the 1-D dataset `set` (its file dataspace `space`).
std::vector<double> read_slice(hid_t set, hid_t space, const char* name, const std::string& path,
                               const detail::Slice& slice) {
  std::vector<double> v(slice.count);
  const hsize_t start = slice.first, count = slice.count;
  const Id mem{H5Screate_simple(1, &count, nullptr), H5Sclose};
  const bool ok = mem.id >= 0 &&
                  (count == 0 ? H5Sselect_none(space) >= 0 && H5Sselect_none(mem.id) >= 0
                              : H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, nullptr, &count,
                                                    nullptr) >= 0) &&
                  H5Dread(set, H5T_NATIVE_DOUBLE, mem.id, space, H5P_DEFAULT, v.data()) >= 0;
  if (!ok) throw Error(path + ": cannot read the checkpoint dataset " + name);
  return v;
}

/// The dataset `name` of `file`: 64-bit floats in one dimension, of a length `len` allows and
/// the file can hold, all checked before it is read; with `slice`, only its values [first,
/// first + count) of a dataset that has any (none of an empty one); `length` gets the dataset's.
std::vector<double> read_vector(hid_t file, const char* name, const std::string& path,
                                const Length& len, const detail::Slice* slice = nullptr,
                                std::size_t* length = nullptr) {
  const Id set{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  if (set.id < 0) throw Error(path + ": not an emcontact checkpoint (no dataset " + name + ")");
  const Id type{H5Dget_type(set.id), H5Tclose};
  if (type.id < 0 || H5Tget_class(type.id) != H5T_FLOAT || H5Tget_size(type.id) != 8)
    refuse_dataset(path, name, "does not hold 64-bit floats (allowed: what emcontact writes)");
  const Id space{H5Dget_space(set.id), H5Sclose};
  const int rank = space.id < 0 ? -1 : H5Sget_simple_extent_ndims(space.id);
  if (rank != 1 || H5Sget_simple_extent_type(space.id) != H5S_SIMPLE)
    refuse_dataset(path, name,
                   "has " + std::to_string(rank) + " dimensions (allowed: 1, a list of values)");
  hsize_t n = 0;
  if (H5Sget_simple_extent_dims(space.id, &n, nullptr) != 1)
    refuse_dataset(path, name, "has no readable length");
  hsize_t bytes = 0;  // a corrupt size must not allocate more than the file can hold
  if (H5Fget_filesize(file, &bytes) < 0 || n > bytes / sizeof(double))
    refuse_dataset(path, name, "claims more values than the file holds");
  if (!len.ok(static_cast<std::size_t>(n)))
    refuse_dataset(path, name,
                   "has " + std::to_string(n) + " values (allowed: " + len.allowed + ")");
  if (length) *length = static_cast<std::size_t>(n);
  if (slice && n > 0) return read_slice(set.id, space.id, name, path, *slice);
  std::vector<double> v(n);
  if (n && H5Dread(set.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw Error(path + ": cannot read the checkpoint dataset " + name);
  return v;
}

/// A dataset that older checkpoints lack: empty if the file has none.
std::vector<double> read_optional_vector(hid_t file, const char* name, const std::string& path,
                                         const Length& len) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return {};
  return read_vector(file, name, path, len);
}

/// The lengths of u and V (`optional`: also none, for last_increment): `values` if the model is
/// known.
Length dof_length(const CheckpointShape* shape, bool optional) {
  if (!shape) return {[](std::size_t) { return true; }, "any"};
  const std::size_t m = shape->values;
  return {[=](std::size_t n) { return n == m || (optional && n == 0); },
          (optional ? "0 or " : "") + std::to_string(m) + ", 3 per node of the input's mesh"};
}

/// The datasets, each checked against `shape` (if any) and the ones read before it.
void read_datasets(hid_t file, Checkpoint& c, const std::string& path, const CheckpointShape* shape,
                   const detail::Slice* slice = nullptr, bool* increment = nullptr) {
  c.set_scalars(read_vector(file, "scalars", path,
                            {[](std::size_t n) { return n >= 6 && n <= 8; }, "6 to 8"}),
                path);
  std::size_t values = 0;
  c.u = read_vector(file, "u", path, dof_length(shape, false), slice, &values);
  c.V = read_vector(
      file, "V", path,
      {[&](std::size_t n) { return n == values; }, std::to_string(values) + ", as many as u"},
      slice);
  std::size_t increments = 0;
  c.last_increment = read_vector(file, "last_increment", path,
                                 {[&](std::size_t n) { return n == values || n == 0; },
                                  "0 or " + std::to_string(values) + ", as many as u"},
                                 slice, &increments);
  if (increment) *increment = increments > 0;
  const std::size_t most = shape ? shape->max_entries * kActiveValues : std::size_t(-1);
  c.active = read_vector(
      file, "active", path,
      {[&](std::size_t n) { return n % kActiveValues == 0 && n <= most; },
       std::to_string(kActiveValues) + " per active node" +
           (shape ? ", at most " + std::to_string(shape->max_entries) + " slave nodes" : "")});
  const std::size_t entries = c.active.size() / kActiveValues;
  c.normal_force = read_vector(file, "normal_force", path,
                               {[&](std::size_t n) { return n == entries; },
                                std::to_string(entries) + ", 1 per active node"});
  // absent before §11.7: all stick
  c.state =
      read_optional_vector(file, "state", path,
                           {[&](std::size_t n) { return n == 0 || n == entries * kStateValues; },
                            "0 or " + std::to_string(entries * kStateValues) + ", " +
                                std::to_string(kStateValues) + " per active node"});
}

/// The model fingerprint and the checksum: present (else an older checkpoint, refused); the
/// model is handed to `shape.check_model` before any dataset is read.
std::uint64_t read_integrity(hid_t file, Checkpoint& c, const std::string& path,
                             const CheckpointShape* shape) {
  auto model = detail::read_string_attribute(file, "model", path);
  const auto sum = detail::read_u64_attribute(file, "checksum", path);
  if (!model || !sum)
    throw Error(path +
                ": written by an older emcontact (no model fingerprint or checksum); "
                "such checkpoints cannot be checked: run again from the start");
  c.model = std::move(*model);
  if (shape && shape->check_model) shape->check_model(c.model);
  return *sum;
}

Checkpoint read(const std::string& path, const CheckpointShape* shape) {
  input::check_regular_file(path, "checkpoint");
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw Error(path + ": not an HDF5 file");
  Checkpoint c;
  try {
    const std::uint64_t sum = read_integrity(file, c, path, shape);
    read_datasets(file, c, path, shape);
    if (detail::checksum(c) != sum)
      throw Error(path + ": the checksum does not match the contents (the file is corrupt)");
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
  return c;
}

}  // namespace

namespace detail {

Checkpoint read_block(const std::string& path, const CheckpointShape& shape, const Slice& slice,
                      std::uint64_t& sum, bool& increment) {
  input::check_regular_file(path, "checkpoint");
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw Error(path + ": not an HDF5 file");
  Checkpoint c;
  try {
    sum = read_integrity(file, c, path, &shape);
    read_datasets(file, c, path, &shape, &slice, &increment);
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
  return c;
}

}  // namespace detail

std::vector<double> Checkpoint::scalars() const {
  return {double(step),       t,         dt, last_h, double(good_steps), double(last_iterations),
          newton_contraction, nominal_dt};
}

void Checkpoint::set_scalars(const std::vector<double>& s, const std::string& path) {
  if (s.size() < 6 || s.size() > 8) throw Error(path + ": bad checkpoint scalars");
  const char* names[] = {"step", "good_steps", "last_iterations"};
  for (int k : {0, 4, 5})  // counters: whole numbers, castable
    if (!(s[k] >= 0 && s[k] <= 9e15 && s[k] == std::floor(s[k])))
      throw Error(path + ": the checkpoint's " + names[k == 0 ? 0 : k - 3] + " (" +
                  std::to_string(s[k]) + ") is not a count");
  step = static_cast<long>(s[0]);
  t = s[1];
  dt = s[2];
  last_h = s[3];
  good_steps = static_cast<int>(s[4]);
  last_iterations = static_cast<int>(s[5]);
  newton_contraction = s.size() > 6 ? s[6] : 0.0;  // absent before the inexact Newton
  nominal_dt = s.size() > 7 ? s[7] : 0.0;
}

void write_checkpoint(const Directory& dir, const std::string& name, const Checkpoint& c) {
  const std::string path = dir.path(name);
  // built in memory, then written atomically: a failed write keeps the previous checkpoint
  write_hdf5_file(dir, name, [&](hid_t file) {
    write_vector(file, "scalars", c.scalars(), path);
    write_vector(file, "u", c.u, path);
    write_vector(file, "V", c.V, path);
    write_vector(file, "last_increment", c.last_increment, path);
    write_vector(file, "active", c.active, path);
    write_vector(file, "normal_force", c.normal_force, path);
    write_vector(file, "state", c.state, path);
    detail::write_string_attribute(file, "model", c.model, path);
    detail::write_u64_attribute(file, "checksum", detail::checksum(c), path);
  });
}

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  write_checkpoint(directory_of(path), base_name(path), c);
}

Checkpoint read_checkpoint(const std::string& path, const CheckpointShape& shape) {
  return read(path, &shape);
}

Checkpoint read_checkpoint(const std::string& path) {
  return read(path, nullptr);
}

}  // namespace emc::output
