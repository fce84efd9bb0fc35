// FieldWriter: HDF5 files read back with the C API; XDMF index well-formed and complete.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/fields.hpp"
#include "fake_mesh.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::FakeMesh;
using testing::has_temp_file;
using testing::make_fake_frame;
using testing::make_fake_mesh;
using testing::slurp;
using testing::TempDir;

/// One dataset read back: its shape, its HDF5 type class/size, and its values as T.
template <typename T>
struct Dataset {
  std::vector<hsize_t> dims;
  H5T_class_t type_class = H5T_NO_CLASS;
  std::size_t type_size = 0;
  std::vector<T> values;
};

/// Reads dataset `name` of file `path` converted to `mem_type`.
template <typename T>
Dataset<T> read_dataset(const std::string& path, const char* name, hid_t mem_type) {
  Dataset<T> d;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << path;
  if (file < 0) return d;
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(set, 0) << path << ":" << name;
  if (set >= 0) {
    const hid_t space = H5Dget_space(set);
    const int rank = H5Sget_simple_extent_ndims(space);
    d.dims.resize(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space, d.dims.data(), nullptr);
    const hid_t type = H5Dget_type(set);
    d.type_class = H5Tget_class(type);
    d.type_size = H5Tget_size(type);
    H5Tclose(type);
    hsize_t count = 1;
    for (hsize_t n : d.dims) count *= n;
    d.values.resize(count);
    if (count > 0) {
      EXPECT_GE(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()), 0);
    }
    H5Sclose(space);
    H5Dclose(set);
  }
  H5Fclose(file);
  return d;
}

/// Number of non-overlapping occurrences of `needle` in `hay`.
std::size_t count(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t p = hay.find(needle); p != std::string::npos; p = hay.find(needle, p + 1)) ++n;
  return n;
}

TEST(FieldWriter, MeshFileHasShapesAndValues) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(3);
  const std::string out = dir / "sub/fields";  // created with parents
  FieldWriter w(out, m.X, m.tets, m.body);
  const std::string mesh = out + "/mesh.h5";
  ASSERT_TRUE(std::filesystem::exists(mesh));
  EXPECT_FALSE(has_temp_file(out));

  const auto n = static_cast<hsize_t>(m.num_nodes()), e = static_cast<hsize_t>(m.num_tets());
  const auto geo = read_dataset<double>(mesh, "/geometry", H5T_NATIVE_DOUBLE);
  EXPECT_EQ(geo.dims, (std::vector<hsize_t>{n, 3}));
  EXPECT_EQ(geo.type_class, H5T_FLOAT);
  EXPECT_EQ(geo.type_size, 8u);
  EXPECT_EQ(geo.values, m.X);
  const auto topo = read_dataset<long long>(mesh, "/topology", H5T_NATIVE_LLONG);
  EXPECT_EQ(topo.dims, (std::vector<hsize_t>{e, 4}));
  EXPECT_EQ(topo.type_class, H5T_INTEGER);
  EXPECT_EQ(topo.type_size, 8u);
  EXPECT_EQ(topo.values, m.tets);
  const auto body = read_dataset<int>(mesh, "/body", H5T_NATIVE_INT);
  EXPECT_EQ(body.dims, (std::vector<hsize_t>{e}));
  EXPECT_EQ(body.type_class, H5T_INTEGER);
  EXPECT_EQ(body.type_size, 4u);
  EXPECT_EQ(body.values, m.body);
}

TEST(FieldWriter, FramesReadBackAndXdmfReferencesEveryFrame) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(2);
  FieldWriter w(dir.path(), m.X, m.tets, m.body);
  const std::vector<long> steps = {0, 7, 123456};
  for (long s : steps) w.write(make_fake_frame(m, s));
  EXPECT_FALSE(has_temp_file(dir.path()));

  const auto n = static_cast<hsize_t>(m.num_nodes()), e = static_cast<hsize_t>(m.num_tets());
  for (long s : steps) {
    const FieldFrame ref = make_fake_frame(m, s);
    char name[64];
    std::snprintf(name, sizeof(name), "fields_%08ld.h5", s);
    const std::string file = dir / name;
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const auto u = read_dataset<double>(file, "/displacement", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(u.dims, (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(u.values, ref.displacement);
    const auto v = read_dataset<double>(file, "/velocity", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(v.dims, (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(v.values, ref.velocity);
    const auto vm = read_dataset<double>(file, "/von_mises", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(vm.dims, (std::vector<hsize_t>{e}));
    EXPECT_EQ(vm.values, ref.von_mises);
    const auto t = read_dataset<double>(file, "/time", H5T_NATIVE_DOUBLE);
    EXPECT_TRUE(t.dims.empty());  // scalar
    ASSERT_EQ(t.values.size(), 1u);
    EXPECT_EQ(t.values[0], ref.time);
  }

  const std::string xdmf = slurp(dir / "fields.xdmf");
  ASSERT_FALSE(xdmf.empty());
  EXPECT_EQ(xdmf.rfind("<?xml", 0), 0u);
  EXPECT_NE(xdmf.find("GridType=\"Collection\" CollectionType=\"Temporal\""), std::string::npos);
  // Well-formed enough: balanced tags we emit, one Grid per frame plus the collection.
  EXPECT_EQ(count(xdmf, "<Grid "), steps.size() + 1);
  EXPECT_EQ(count(xdmf, "</Grid>"), steps.size() + 1);
  EXPECT_EQ(count(xdmf, "<Time "), steps.size());
  EXPECT_EQ(count(xdmf, "<DataItem "), count(xdmf, "</DataItem>"));
  EXPECT_EQ(count(xdmf, "<Attribute "), 7 * steps.size());  // + contact_status, normal_force, slip
  EXPECT_EQ(count(xdmf, "TopologyType=\"Tetrahedron\""), steps.size());
  EXPECT_EQ(count(xdmf, "GeometryType=\"XYZ\""), steps.size());
  EXPECT_EQ(count(xdmf, "AttributeType=\"Vector\" Center=\"Node\""), 2 * steps.size());
  EXPECT_EQ(count(xdmf, "Center=\"Cell\""), 2 * steps.size());
  EXPECT_NE(xdmf.find("</Xdmf>"), std::string::npos);
  // Every referenced HDF5 file exists, relative to the XDMF file; every frame is referenced.
  const std::regex ref(R"(>([^<>:]+\.h5):(/[a-z_]+)</DataItem>)");
  std::set<std::string> files;
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), ref); it != std::sregex_iterator();
       ++it) {
    files.insert((*it)[1]);
    EXPECT_TRUE(std::filesystem::exists(dir / (*it)[1].str())) << (*it)[1];
  }
  EXPECT_EQ(files, (std::set<std::string>{"mesh.h5", "fields_00000000.h5", "fields_00000007.h5",
                                          "fields_00123456.h5"}));
  EXPECT_NE(xdmf.find("<Time Value=\"0.70000000000000007\"/>"), std::string::npos);
}

TEST(FieldWriter, RewritingAStepReplacesItsFrame) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(1);
  FieldWriter w(dir.path(), m.X, m.tets, m.body);
  w.write(make_fake_frame(m, 1));
  w.write(make_fake_frame(m, 2));
  w.write(make_fake_frame(m, 2));
  EXPECT_EQ(count(slurp(dir / "fields.xdmf"), "<Time "), 2u);
}

TEST(FieldWriter, FramesAreAddedToTheIndexNotRewritingIt) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(1);
  FieldWriter w(dir.path(), m.X, m.tets, m.body);
  w.write(make_fake_frame(m, 0));
  struct stat first {};
  ASSERT_EQ(::stat((dir / "fields.xdmf").c_str(), &first), 0);
  for (long s = 1; s <= 30; ++s) w.write(make_fake_frame(m, s));
  struct stat later {};
  ASSERT_EQ(::stat((dir / "fields.xdmf").c_str(), &later), 0);
  EXPECT_EQ(first.st_ino, later.st_ino) << "the index was replaced, not added to";
  const std::string added = slurp(dir / "fields.xdmf");
  EXPECT_EQ(count(added, "<Time "), 31u);
  // the independent reference: the index written whole from the frame files (a restart's)
  FieldWriter again(dir.path(), m.X, m.tets, m.body);
  again.resume(30);
  EXPECT_EQ(slurp(dir / "fields.xdmf"), added);
  EXPECT_FALSE(has_temp_file(dir.path()));
}

TEST(FieldWriter, WrongSizesThrow) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(1);
  EXPECT_THROW(FieldWriter(dir.path(), {0.0, 1.0}, m.tets, m.body), emc::Error);
  EXPECT_THROW(FieldWriter(dir.path(), m.X, m.tets, {}), emc::Error);
  FieldWriter w(dir.path(), m.X, m.tets, m.body);
  FieldFrame f = make_fake_frame(m, 0);
  f.von_mises.pop_back();
  EXPECT_THROW(w.write(f), emc::Error);
}

TEST(FieldWriter, UncreatableDirectoryThrowsNamingIt) {
  TempDir dir;
  atomic_write(dir / "file", "x");
  const FakeMesh m = make_fake_mesh(1);
  const std::string out = dir / "file/fields";
  try {
    FieldWriter w(out, m.X, m.tets, m.body);
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    EXPECT_NE(std::string(e.what()).find(out), std::string::npos) << e.what();
  }
}

TEST(FieldWriter, UnwritableFrameThrowsNamingFile) {
  TempDir dir;
  const FakeMesh m = make_fake_mesh(1);
  FieldWriter w(dir / "out", m.X, m.tets, m.body);
  std::filesystem::remove_all(dir / "out");  // the directory disappears under the writer
  try {
    w.write(make_fake_frame(m, 3));
    FAIL() << "no exception";
  } catch (const emc::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir / "out/fields_00000003.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace emc::output
