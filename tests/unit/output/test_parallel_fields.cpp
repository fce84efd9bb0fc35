// The field files written by every rank together (parallel HDF5, each rank its block of rows)
// hold exactly what one rank writes of the same arrays: every dataset's shape, type and bytes.
// Run on 1, 2 and 3 ranks (uneven blocks; on 3 ranks the one-tet mesh leaves ranks without rows).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "fake_mesh.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::FakeMesh;
using testing::make_fake_frame;
using testing::make_fake_mesh;
using testing::TempDir;

/// The rows [first, first + count) of `v`, `width` values each (none of an empty field).
template <class T>
std::vector<T> rows(const std::vector<T>& v, long long first, long long count, int width) {
  if (v.empty()) return v;
  return std::vector<T>(v.begin() + width * first, v.begin() + width * (first + count));
}

/// The fake frame of `step` with contact fields too (distinct values per node).
FieldFrame frame(const FakeMesh& m, long step) {
  FieldFrame f = make_fake_frame(m, step);
  for (long long n = 0; n < m.num_nodes(); ++n) {
    f.contact_status.push_back(static_cast<double>(n % 3));
    f.normal_force.push_back(0.5 * static_cast<double>(n + step));
    f.slip.push_back(static_cast<double>((n + step) % 2));
  }
  return f;
}

/// This rank's rows of a whole frame.
FieldFrame my_rows(const FieldFrame& f, const FieldLayout& l) {
  FieldFrame r = f;
  r.displacement = rows(f.displacement, l.node_first, l.node_count, 3);
  r.velocity = rows(f.velocity, l.node_first, l.node_count, 3);
  r.von_mises = rows(f.von_mises, l.tet_first, l.tet_count, 1);
  r.contact_status = rows(f.contact_status, l.node_first, l.node_count, 1);
  r.normal_force = rows(f.normal_force, l.node_first, l.node_count, 1);
  r.slip = rows(f.slip, l.node_first, l.node_count, 1);
  return r;
}

/// Dataset `name` of `path`: its dims, its file type's class and size, its raw bytes.
struct Raw {
  std::vector<hsize_t> dims;
  H5T_class_t cls = H5T_NO_CLASS;
  std::size_t size = 0;
  std::vector<char> bytes;
  bool operator==(const Raw& o) const {
    return dims == o.dims && cls == o.cls && size == o.size && bytes == o.bytes;
  }
};

Raw read_raw(const std::string& path, const char* name) {
  Raw r;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << path;
  if (file < 0) return r;
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(set, 0) << path << ":" << name;
  const hid_t space = H5Dget_space(set), type = H5Dget_type(set);
  r.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, r.dims.data(), nullptr);
  r.cls = H5Tget_class(type);
  r.size = H5Tget_size(type);
  r.bytes.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)) * r.size);
  if (!r.bytes.empty())
    EXPECT_GE(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.bytes.data()), 0);
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  return r;
}

/// Writes mesh.h5 and frames 0 and 5 of `m` on every rank into `par` (each rank its rows) and
/// on rank 0 alone into `ser`; rank 0 compares every dataset of the two.
void expect_same_files(const FakeMesh& m) {
  TempDir* dir = rank_of(MPI_COMM_WORLD) == 0 ? new TempDir : nullptr;
  const std::string base = broadcast(MPI_COMM_WORLD, dir ? dir->path() : std::string());
  const std::string par = base + "/par", ser = base + "/ser";
  if (rank_of(MPI_COMM_WORLD) == 0) {
    ASSERT_EQ(::mkdir(par.c_str(), 0755), 0);
    ASSERT_EQ(::mkdir(ser.c_str(), 0755), 0);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const auto l = FieldLayout::blocks(MPI_COMM_WORLD, m.num_nodes(), m.num_tets());
  {
    const Directory root_dir = rank_of(MPI_COMM_WORLD) == 0 ? Directory(par) : Directory();
    FieldWriter w(
        shared_directory(MPI_COMM_WORLD, root_dir), l, rows(m.X, l.node_first, l.node_count, 3),
        rows(m.tets, l.tet_first, l.tet_count, 4), rows(m.body, l.tet_first, l.tet_count, 1));
    for (long step : {0L, 5L}) w.write(my_rows(frame(m, step), l));
  }
  if (rank_of(MPI_COMM_WORLD) == 0) {
    FieldWriter w(ser, m.X, m.tets, m.body);
    for (long step : {0L, 5L}) w.write(frame(m, step));
    for (const char* set : {"/geometry", "/topology", "/body"})
      EXPECT_TRUE(read_raw(par + "/mesh.h5", set) == read_raw(ser + "/mesh.h5", set)) << set;
    for (const char* f : {"/fields_00000000.h5", "/fields_00000005.h5"})
      for (const char* set : {"/displacement", "/velocity", "/von_mises", "/contact_status",
                              "/normal_force", "/slip", "/time", "/step"})
        EXPECT_TRUE(read_raw(par + f, set) == read_raw(ser + f, set)) << f << set;
    EXPECT_EQ(testing::slurp(par + "/fields.xdmf"), testing::slurp(ser + "/fields.xdmf"));
  }
  MPI_Barrier(MPI_COMM_WORLD);
  delete dir;
}

TEST(ParallelFields, EveryRanksRowsMakeTheSameFilesAsOneRank) {
  expect_same_files(make_fake_mesh(3));  // 64 nodes, 162 tets
}

TEST(ParallelFields, RanksWithoutRowsTakePart) {
  FakeMesh m;  // one tet: on 3 ranks two of them hold no tet
  m.X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.tets = {0, 1, 2, 3};
  m.body = {0};
  expect_same_files(m);
}

TEST(ParallelFields, AFailedWriteStopsEveryRankNamingTheFile) {
  TempDir* dir = rank_of(MPI_COMM_WORLD) == 0 ? new TempDir : nullptr;
  const std::string out = broadcast(MPI_COMM_WORLD, dir ? (*dir / "out") : std::string());
  if (rank_of(MPI_COMM_WORLD) == 0) ASSERT_EQ(::mkdir(out.c_str(), 0755), 0);
  MPI_Barrier(MPI_COMM_WORLD);
  const FakeMesh m = make_fake_mesh(2);
  const auto l = FieldLayout::blocks(MPI_COMM_WORLD, m.num_nodes(), m.num_tets());
  const Directory root_dir = rank_of(MPI_COMM_WORLD) == 0 ? Directory(out) : Directory();
  FieldWriter w(shared_directory(MPI_COMM_WORLD, root_dir), l,
                rows(m.X, l.node_first, l.node_count, 3), rows(m.tets, l.tet_first, l.tet_count, 4),
                rows(m.body, l.tet_first, l.tet_count, 1));
  // the directory removed under the run: rank 0 cannot create the frame's temporary
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank_of(MPI_COMM_WORLD) == 0) std::filesystem::remove_all(out);
  MPI_Barrier(MPI_COMM_WORLD);
  try {
    w.write(my_rows(frame(m, 1), l));
    ADD_FAILURE() << "no error on rank " << rank_of(MPI_COMM_WORLD);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fields_00000001.h5"), std::string::npos) << e.what();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  delete dir;
}

TEST(ParallelFields, AnotherDirectoryAtTheNameIsRefused) {
  TempDir* dir = rank_of(MPI_COMM_WORLD) == 0 ? new TempDir : nullptr;
  const std::string out = broadcast(MPI_COMM_WORLD, dir ? (*dir / "out") : std::string());
  if (rank_of(MPI_COMM_WORLD) == 0) ASSERT_EQ(::mkdir(out.c_str(), 0755), 0);
  MPI_Barrier(MPI_COMM_WORLD);
  const Directory root_dir = rank_of(MPI_COMM_WORLD) == 0 ? Directory(out) : Directory();
  if (rank_of(MPI_COMM_WORLD) ==
      0) {  // renamed after rank 0 opened it, another one made at its name
    ASSERT_EQ(::rename(out.c_str(), (out + ".moved").c_str()), 0);
    ASSERT_EQ(::mkdir(out.c_str(), 0755), 0);
  }
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks > 1) {
    EXPECT_THROW(shared_directory(MPI_COMM_WORLD, root_dir), Error);
  } else {
    EXPECT_NO_THROW(shared_directory(MPI_COMM_WORLD, root_dir));  // rank 0 keeps its own
  }
  MPI_Barrier(MPI_COMM_WORLD);
  delete dir;
}

}  // namespace
}  // namespace emc::output
