// HDF5 files built in memory and written atomically (see hdf5_file.hpp).
#include "emcontact/output/hdf5_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"

namespace emc::output {
namespace {

/// The name HDF5 gets for the in-memory file. H5Fcreate first tries to open an existing file of
/// that name (read-write) to see if it is open already; a path under /dev/null can never be
/// opened, so nothing on disk (e.g. a link planted at `path`) is ever touched.
constexpr const char* kMemoryName = "/dev/null/emcontact-in-memory.h5";

/// The growth step of the in-memory file image.
constexpr std::size_t kImageIncrement = std::size_t(1) << 20;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error("cannot write '" + path + "': " + what);
}

/// A file access property list for the core driver without a backing store.
hid_t in_memory_access(const std::string& path) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) fail(path, "HDF5 cannot create a file access list");
  if (H5Pset_fapl_core(fapl, kImageIncrement, 0) < 0) {
    H5Pclose(fapl);
    fail(path, "HDF5 cannot select the in-memory driver");
  }
  return fapl;
}

/// The bytes of the open in-memory file `file`.
std::string file_image(hid_t file, const std::string& path) {
  if (H5Fflush(file, H5F_SCOPE_LOCAL) < 0) fail(path, "HDF5 cannot flush the file");
  const ssize_t n = H5Fget_file_image(file, nullptr, 0);
  if (n < 0) fail(path, "HDF5 cannot size the file image");
  std::string image(static_cast<std::size_t>(n), '\0');
  if (n > 0 && H5Fget_file_image(file, image.data(), image.size()) != n)
    fail(path, "HDF5 cannot copy the file image");
  return image;
}

}  // namespace

void write_hdf5_file(const Directory& dir, const std::string& name,
                     const std::function<void(hid_t)>& fill) {
  const std::string path = dir.path(name);
  const hid_t fapl = in_memory_access(path);
  const hid_t file = H5Fcreate(kMemoryName, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  if (file < 0) fail(path, "HDF5 cannot create the file in memory");
  std::string image;
  try {
    fill(file);
    image = file_image(file, path);
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  if (H5Fclose(file) < 0) fail(path, "HDF5 cannot close the file");
  atomic_write(dir, name, image);
}

void write_hdf5_file(const std::string& path, const std::function<void(hid_t)>& fill) {
  write_hdf5_file(directory_of(path), base_name(path), fill);
}

hid_t open_hdf5_file(const Directory& dir, const std::string& name) {
  const int fd = ::openat(dir.fd(), name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return -1;
  struct stat st {};
  hid_t file = -1;
  // the file the descriptor holds, by its /proc name: HDF5 opens only by name
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode))
    file = H5Fopen(("/proc/self/fd/" + std::to_string(fd)).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ::close(fd);  // HDF5 holds its own descriptor
  return file;
}

void silence_hdf5_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

}  // namespace emc::output
