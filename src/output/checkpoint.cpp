#include "emcontact/output/checkpoint.hpp"

#include <hdf5.h>
#include <unistd.h>

#include "emcontact/error.hpp"
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
  std::vector<double> v(n);
  const herr_t st =
      n ? H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) : 0;
  H5Sclose(space);
  H5Dclose(set);
  if (st < 0) throw Error(path + ": cannot read the checkpoint dataset " + name);
  return v;
}

}  // namespace

std::vector<double> Checkpoint::scalars() const {
  return {double(step),      t, dt, last_h, double(good_steps), double(last_iterations),
          newton_contraction};
}

void Checkpoint::set_scalars(const std::vector<double>& s, const std::string& path) {
  if (s.size() != 6 && s.size() != 7) throw Error(path + ": bad checkpoint scalars");
  step = static_cast<long>(s[0]);
  t = s[1];
  dt = s[2];
  last_h = s[3];
  good_steps = static_cast<int>(s[4]);
  last_iterations = static_cast<int>(s[5]);
  newton_contraction = s.size() > 6 ? s[6] : 0.0;  // absent before the inexact Newton
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
  });
}

Checkpoint read_checkpoint(const std::string& path) {
  if (access(path.c_str(), R_OK) != 0) throw Error(path + ": cannot read the checkpoint file");
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
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
  return c;
}

}  // namespace emc::output
