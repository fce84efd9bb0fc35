#include "emcontact/output/checkpoint.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <cmath>

#include "checkpoint_meta.hpp"
#include "emcontact/error.hpp"
#include "emcontact/input/files.hpp"
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

std::vector<double> read_vector(hid_t file, const char* name, const std::string& path) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  if (set < 0) throw Error(path + ": not an emcontact checkpoint (no dataset " + name + ")");
  const hid_t space = H5Dget_space(set);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  hsize_t bytes = 0;  // a corrupt size must not allocate more than the file can hold
  if (H5Fget_filesize(file, &bytes) < 0 || n > bytes / sizeof(double)) {
    H5Sclose(space);
    H5Dclose(set);
    throw Error(path + ": the checkpoint dataset " + name +
                " claims more values than the file holds");
  }
  std::vector<double> v(n);
  const herr_t st =
      n ? H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) : 0;
  H5Sclose(space);
  H5Dclose(set);
  if (st < 0) throw Error(path + ": cannot read the checkpoint dataset " + name);
  return v;
}

/// A dataset that older checkpoints lack: empty if the file has none.
std::vector<double> read_optional_vector(hid_t file, const char* name, const std::string& path) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return {};
  return read_vector(file, name, path);
}

/// The model fingerprint and the checksum: present (else an older checkpoint, refused) and
/// matching the contents.
void check_integrity(hid_t file, Checkpoint& c, const std::string& path) {
  auto model = detail::read_string_attribute(file, "model", path);
  const auto sum = detail::read_u64_attribute(file, "checksum", path);
  if (!model || !sum)
    throw Error(path +
                ": written by an older emcontact (no model fingerprint or checksum); "
                "such checkpoints cannot be checked: run again from the start");
  c.model = std::move(*model);
  if (detail::checksum(c) != *sum)
    throw Error(path + ": the checksum does not match the contents (the file is corrupt)");
}

}  // namespace

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

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  // built in memory, then written atomically: a failed write keeps the previous checkpoint
  write_hdf5_file(path, [&](hid_t file) {
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

Checkpoint read_checkpoint(const std::string& path) {
  input::check_regular_file(path, "checkpoint");
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw Error(path + ": not an HDF5 file");
  Checkpoint c;
  try {
    c.set_scalars(read_vector(file, "scalars", path), path);
    c.u = read_vector(file, "u", path);
    c.V = read_vector(file, "V", path);
    c.last_increment = read_vector(file, "last_increment", path);
    c.active = read_vector(file, "active", path);
    c.normal_force = read_vector(file, "normal_force", path);
    c.state = read_optional_vector(file, "state", path);  // absent before §11.7: all stick
    check_integrity(file, c, path);
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
  return c;
}

}  // namespace emc::output
