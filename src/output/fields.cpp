// Field output: DIR/mesh.h5 once, DIR/fields_<step>.h5 per frame, DIR/fields.xdmf as the index
// ParaView opens (a temporal collection of tetrahedral grids sharing mesh.h5).
#include "emcontact/output/fields.hpp"

#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <utility>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/directory.hpp"
#include "emcontact/output/hdf5_file.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "hdf5_util.hpp"

namespace emc::output {
namespace {

using detail::Handle;
using detail::hdf5_error_text;
using detail::SilenceHdf5Errors;

// ---------------------------------------------------------------------------------------------
// HDF5 helpers

/// Throws emc::Error naming `path` and what failed.
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error("cannot write HDF5 file '" + path + "': " + what + ": " + hdf5_error_text());
}

/// Writes one contiguous (unchunked, uncompressed: fastest) dataset, whole, into `file`.
void write_dataset(hid_t file, const std::string& path, const SlabDataset& d) {
  const hsize_t dims[2] = {d.rows, d.width};
  Handle space(
      d.width == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(d.width == 1 ? 1 : 2, dims, nullptr),
      H5Sclose);
  if (!space.valid()) fail(path, "dataspace of " + d.name);
  Handle set(H5Dcreate2(file, d.name.c_str(), d.file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose);
  if (!set.valid()) fail(path, "creating dataset " + d.name);
  // HDF5 refuses a null buffer even for zero elements: skip the (empty) write.
  const bool empty = d.width > 0 && d.rows == 0;
  if (!empty && H5Dwrite(set.get(), d.mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.data) < 0)
    fail(path, "writing dataset " + d.name);
  if (!set.reset()) fail(path, "closing dataset " + d.name);
}

/// Writes `datasets` into a new HDF5 file `name` of `dir`, atomically: on one rank built in
/// memory, then renamed; on several, each rank's rows written in place into a temporary, then
/// renamed (collective).
void write_hdf5_atomically(const Directory& dir, const FieldLayout& layout, const std::string& name,
                           const std::vector<SlabDataset>& datasets) {
  SilenceHdf5Errors quiet;
  if (ranks_of(layout.comm) > 1) return write_hdf5_collectively(layout.comm, dir, name, datasets);
  const std::string path = dir.path(name);
  write_hdf5_file(dir, name, [&](hid_t file) {
    for (const SlabDataset& d : datasets) write_dataset(file, path, d);
  });
}

/// A dataset of `rows` rows of `width` values (0: a scalar) of which this rank holds rows
/// [first, first + count) in `data`.
SlabDataset slab(const char* name, hid_t file_type, hid_t mem_type, long long rows, int width,
                 long long first, long long count, const void* data) {
  SlabDataset d{name, file_type, mem_type};
  d.rows = static_cast<unsigned long long>(rows);
  d.width = static_cast<unsigned long long>(width);
  d.offset = static_cast<unsigned long long>(first);
  d.count = static_cast<unsigned long long>(count);
  d.data = data;
  return d;
}

// ---------------------------------------------------------------------------------------------
// XDMF helpers

/// A double as "%.17g" (exact round trip, locale independent).
std::string format_double(double v) {
  std::array<char, 64> buf;
  const auto res =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 17);
  return std::string(buf.data(), res.ptr);
}

/// An XDMF HDF DataItem: `dims` like "1000 3", `type` "Float"/"Int", precision in bytes.
std::string data_item(const std::string& dims, const char* type, int precision,
                      const std::string& ref, const char* indent) {
  return std::string(indent) + "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type +
         "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" + ref +
         "</DataItem>\n";
}

/// An XDMF Attribute wrapping one DataItem.
std::string attribute(const char* name, const char* type, const char* center,
                      const std::string& item) {
  return std::string("        <Attribute Name=\"") + name + "\" AttributeType=\"" + type +
         "\" Center=\"" + center + "\">\n" + item + "        </Attribute>\n";
}

// ---------------------------------------------------------------------------------------------
// Frames already in the directory (restart)

/// Reads the time stored in the frame file `name` of `dir`; false if it is not a readable frame
/// (a regular file only: a FIFO would block the open; a scalar or one-value float dataset).
bool read_frame_time(const Directory& dir, const std::string& name, double& time) {
  SilenceHdf5Errors quiet;
  Handle file(open_hdf5_file(dir, name), H5Fclose);
  if (!file.valid()) return false;
  Handle set(H5Dopen2(file.get(), "/time", H5P_DEFAULT), H5Dclose);
  if (!set.valid()) return false;
  Handle space(H5Dget_space(set.get()), H5Sclose);
  Handle type(H5Dget_type(set.get()), H5Tclose);
  if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1) return false;
  if (!type.valid() || H5Tget_class(type.get()) != H5T_FLOAT) return false;
  return H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &time) >= 0;
}

/// The directory `dir`, created if missing, opened by name.
Directory made_directory(const std::string& dir) {
  make_directory(dir);
  return Directory(dir, true);
}

}  // namespace

FieldLayout FieldLayout::blocks(MPI_Comm comm, long long nodes, long long tets) {
  int rank = 0;
  const int ranks = ranks_of(comm);
  if (ranks > 1) MPI_Comm_rank(comm, &rank);
  const Block n = block_of(nodes, rank, ranks), e = block_of(tets, rank, ranks);
  return {comm, nodes, tets, n.first, n.count, e.first, e.count};
}

FieldWriter::FieldWriter(const std::string& dir, const std::vector<double>& X,
                         const std::vector<long long>& tets, const std::vector<int>& body_of_tet)
    : FieldWriter(made_directory(dir), X, tets, body_of_tet) {}

FieldWriter::FieldWriter(Directory dir, const std::vector<double>& X,
                         const std::vector<long long>& tets, const std::vector<int>& body_of_tet)
    : FieldWriter(std::move(dir),
                  FieldLayout::blocks(MPI_COMM_SELF, static_cast<long long>(X.size() / 3),
                                      static_cast<long long>(tets.size() / 4)),
                  X, tets, body_of_tet) {}

FieldWriter::FieldWriter(Directory dir, const FieldLayout& layout, const std::vector<double>& X,
                         const std::vector<long long>& tets, const std::vector<int>& body_of_tet)
    : dir_(std::move(dir)), layout_(layout) {
  const auto nodes = static_cast<std::size_t>(layout.node_count);
  const auto elems = static_cast<std::size_t>(layout.tet_count);
  if (X.size() != 3 * nodes) throw Error("FieldWriter: node coordinates are not 3 per node");
  if (tets.size() != 4 * elems) throw Error("FieldWriter: tetrahedra are not 4 nodes each");
  if (body_of_tet.size() != elems) {
    throw Error("FieldWriter: " + std::to_string(body_of_tet.size()) + " body ids for " +
                std::to_string(elems) + " tetrahedra");
  }
  const long long n = layout.num_nodes, e = layout.num_tets;
  const long long n0 = layout.node_first, e0 = layout.tet_first;
  write_hdf5_atomically(
      dir_, layout_, "mesh.h5",
      {slab("/geometry", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 3, n0, nodes, X.data()),
       slab("/topology", H5T_STD_I64LE, H5T_NATIVE_LLONG, e, 4, e0, elems, tets.data()),
       slab("/body", H5T_STD_I32LE, H5T_NATIVE_INT, e, 1, e0, elems, body_of_tet.data())});
}

void FieldWriter::write(const FieldFrame& f) {
  const auto nodes = static_cast<std::size_t>(layout_.node_count);
  const auto elems = static_cast<std::size_t>(layout_.tet_count);
  if (f.displacement.size() != 3 * nodes || f.velocity.size() != 3 * nodes ||
      f.von_mises.size() != elems) {
    throw Error("FieldWriter: frame of step " + std::to_string(f.step) +
                " has wrong sizes (displacement " + std::to_string(f.displacement.size()) +
                ", velocity " + std::to_string(f.velocity.size()) + ", von_mises " +
                std::to_string(f.von_mises.size()) + "; expected " + std::to_string(3 * nodes) +
                ", " + std::to_string(3 * nodes) + ", " + std::to_string(elems) + ")");
  }
  const long long n = layout_.num_nodes, e = layout_.num_tets;
  const long long n0 = layout_.node_first, e0 = layout_.tet_first;
  const long long step = f.step;
  const std::vector<double> zeros(nodes, 0.0);
  const auto& status = f.contact_status.size() == nodes ? f.contact_status : zeros;
  const auto& normal = f.normal_force.size() == nodes ? f.normal_force : zeros;
  const auto& slip = f.slip.size() == nodes ? f.slip : zeros;
  const hid_t F64 = H5T_IEEE_F64LE, D = H5T_NATIVE_DOUBLE;
  write_hdf5_atomically(dir_, layout_, frame_file_name(f.step),
                        {slab("/displacement", F64, D, n, 3, n0, nodes, f.displacement.data()),
                         slab("/velocity", F64, D, n, 3, n0, nodes, f.velocity.data()),
                         slab("/von_mises", F64, D, e, 1, e0, elems, f.von_mises.data()),
                         slab("/contact_status", F64, D, n, 1, n0, nodes, status.data()),
                         slab("/normal_force", F64, D, n, 1, n0, nodes, normal.data()),
                         slab("/slip", F64, D, n, 1, n0, nodes, slip.data()),
                         slab("/time", F64, D, 1, 0, 0, 1, &f.time),
                         slab("/step", H5T_STD_I64LE, H5T_NATIVE_LLONG, 1, 0, 0, 1, &step)});
  // A step written again (e.g. the final frame) replaces its entry instead of duplicating it.
  auto same = std::find_if(frames_.begin(), frames_.end(),
                           [&](const auto& fr) { return fr.first == f.step; });
  if (same != frames_.end()) {
    same->second = f.time;
    on_root(layout_.comm, [&] { write_xdmf(); });
  } else {
    frames_.emplace_back(f.step, f.time);
    on_root(layout_.comm, [&] { add_to_xdmf(f.step, f.time); });
  }
}

void FieldWriter::resume(long step) {
  on_root(layout_.comm, [&] { resume_root(step); });
}

void FieldWriter::resume_root(long step) {
  frames_.clear();
  for (const std::string& name : dir_.entries()) {
    const long s = frame_step(name);
    if (s < 0) continue;
    if (s > step) {  // written after the checkpoint by the earlier run: no longer valid
      if (::unlinkat(dir_.fd(), name.c_str(), 0) != 0 && errno != ENOENT)
        throw Error("cannot remove '" + dir_.path(name) + "': " + std::strerror(errno));
      continue;
    }
    double time = 0;
    if (read_frame_time(dir_, name, time)) frames_.emplace_back(s, time);
  }
  std::sort(frames_.begin(), frames_.end());
  write_xdmf();
}

namespace {

constexpr const char* kXdmfHead =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
    "  <Domain>\n"
    "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
constexpr const char* kXdmfTail = "    </Grid>\n  </Domain>\n</Xdmf>\n";

}  // namespace

std::string FieldWriter::xdmf_grid(long step, double time) const {
  const std::string n = std::to_string(layout_.num_nodes), e = std::to_string(layout_.num_tets);
  const char* in = "          ";  // DataItem indentation
  const std::string file = frame_file_name(step);
  std::string x = "      <Grid Name=\"step_" + std::to_string(step) + "\" GridType=\"Uniform\">\n";
  x += "        <Time Value=\"" + format_double(time) + "\"/>\n";
  // the mesh parts are the same in every grid
  x += "        <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" + e +
       "\" NodesPerElement=\"4\">\n" + data_item(e + " 4", "Int", 8, "mesh.h5:/topology", in) +
       "        </Topology>\n";
  x += "        <Geometry GeometryType=\"XYZ\">\n" +
       data_item(n + " 3", "Float", 8, "mesh.h5:/geometry", in) + "        </Geometry>\n";
  x += attribute("displacement", "Vector", "Node",
                 data_item(n + " 3", "Float", 8, file + ":/displacement", in));
  x += attribute("velocity", "Vector", "Node",
                 data_item(n + " 3", "Float", 8, file + ":/velocity", in));
  x += attribute("von_mises", "Scalar", "Cell", data_item(e, "Float", 8, file + ":/von_mises", in));
  x += attribute("contact_status", "Scalar", "Node",
                 data_item(n, "Float", 8, file + ":/contact_status", in));
  x += attribute("normal_force", "Scalar", "Node",
                 data_item(n, "Float", 8, file + ":/normal_force", in));
  x += attribute("slip", "Scalar", "Node", data_item(n, "Float", 8, file + ":/slip", in));
  x += attribute("body", "Scalar", "Cell", data_item(e, "Int", 4, "mesh.h5:/body", in));
  x += "      </Grid>\n";
  return x;
}

void FieldWriter::write_xdmf() {
  std::string x = kXdmfHead;
  for (const auto& [step, time] : frames_) x += xdmf_grid(step, time);
  x += kXdmfTail;
  xdmf_.replace(dir_, "fields.xdmf", x);
}

void FieldWriter::add_to_xdmf(long step, double time) {
  if (!xdmf_.is_open()) return write_xdmf();
  const std::size_t at = xdmf_.size() - std::strlen(kXdmfTail);  // the closing tags
  try {
    xdmf_.write_at(at, xdmf_grid(step, time) + kXdmfTail);
  } catch (const Error&) {
    frames_.pop_back();
    try {
      xdmf_.write_at(at, kXdmfTail);  // within the old size: needs no new space
    } catch (const Error&) {
    }
    throw;
  }
}

}  // namespace emc::output
