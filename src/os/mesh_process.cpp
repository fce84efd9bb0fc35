// The meshes built in a child process (see mesh_process.hpp).
#include "emcontact/os/mesh_process.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "emcontact/error.hpp"
#include "emcontact/os/memory.hpp"

namespace emc::os {
namespace {

/// The child's end of the pipe: writes everything or remembers that it could not.
class PipeWriter {
 public:
  explicit PipeWriter(int fd) : fd_(fd) {}
  bool ok() const { return ok_; }
  void bytes(const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    while (ok_ && n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        ok_ = false;
        return;
      }
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  }
  void count(std::uint64_t n) { bytes(&n, sizeof n); }
  template <class T>
  void vec(const std::vector<T>& v) {
    count(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
  void str(const std::string& s) {
    count(s.size());
    bytes(s.data(), s.size());
  }

 private:
  int fd_;
  bool ok_ = true;
};

/// The parent's end: reads exactly what the child wrote; false at an early end.
class PipeReader {
 public:
  explicit PipeReader(int fd) : fd_(fd) {}
  bool bytes(void* data, std::size_t n) {
    char* p = static_cast<char*>(data);
    while (n > 0) {
      const ssize_t r = ::read(fd_, p, n);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return false;
      p += r;
      n -= static_cast<std::size_t>(r);
    }
    return true;
  }
  bool count(std::uint64_t& n, std::uint64_t most) { return bytes(&n, sizeof n) && n <= most; }
  template <class T>
  bool vec(std::vector<T>& v) {
    std::uint64_t n = 0;
    if (!count(n, kMostBytes / sizeof(T))) return false;
    v.resize(n);
    return n == 0 || bytes(v.data(), n * sizeof(T));
  }
  bool str(std::string& s) {
    std::uint64_t n = 0;
    if (!count(n, kMostBytes)) return false;
    s.resize(n);
    return n == 0 || bytes(s.data(), n);
  }

 private:
  static constexpr std::uint64_t kMostBytes = std::uint64_t(1) << 40;
  int fd_;
};

void send(PipeWriter& w, const std::vector<mesh::BodyMesh>& meshes) {
  w.count(meshes.size());
  for (const auto& m : meshes) {
    w.vec(m.X);
    w.vec(m.tets);
    w.count(m.surfaces.size());
    for (const auto& [name, tris] : m.surfaces) {
      w.str(name);
      w.vec(tris);
    }
  }
}

bool receive(PipeReader& r, std::vector<mesh::BodyMesh>& meshes) {
  std::uint64_t n = 0;
  if (!r.count(n, 1u << 20)) return false;
  meshes.resize(n);
  for (auto& m : meshes) {
    std::uint64_t ns = 0;
    if (!r.vec(m.X) || !r.vec(m.tets) || !r.count(ns, 1u << 20)) return false;
    for (std::uint64_t k = 0; k < ns; ++k) {
      std::string name;
      if (!r.str(name) || !r.vec(m.surfaces[name])) return false;
    }
  }
  return true;
}

/// The child: builds, sends a status byte and the meshes or the error text, and leaves without
/// running the parent's exit handlers (MPI, Kokkos).
[[noreturn]] void run_child(int fd, pid_t parent,
                            const std::function<std::vector<mesh::BodyMesh>()>& build) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // the run stopped: so does its mesher
  if (::getppid() != parent) _exit(1);
  for (int s : {SIGTERM, SIGINT, SIGHUP}) std::signal(s, SIG_DFL);  // the parent reports them
  PipeWriter w(fd);
  try {
    const auto meshes = build();
    w.count(1);
    send(w, meshes);
  } catch (const std::exception& e) {
    std::string text = is_out_of_memory(e) ? out_of_memory_message(e) : e.what();
    w.count(0);
    w.str(text.empty() ? "mesh generation failed" : text);
  }
  std::fflush(stdout);
  std::fflush(stderr);
  _exit(w.ok() ? 0 : 1);
}

/// How the child ended, for a message: "was killed by signal 9 (Killed; the kernel's
/// out-of-memory killer sends it)" or "exited with status 1".
std::string ending(int status) {
  if (WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    return "was killed by signal " + std::to_string(s) + " (" + strsignal(s) + ")" +
           (s == SIGKILL ? "; the kernel's out-of-memory killer sends it when memory runs out"
                         : "");
  }
  return "exited with status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

}  // namespace

std::vector<mesh::BodyMesh> build_in_child_process(
    const std::function<std::vector<mesh::BodyMesh>()>& build) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return build();
  std::fflush(stdout);  // nothing buffered is written twice
  std::fflush(stderr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return build();
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], parent, build);
  }
  ::close(fds[1]);
  PipeReader r(fds[0]);
  std::uint64_t ok = 0;
  std::vector<mesh::BodyMesh> meshes;
  std::string error;
  const bool complete = r.count(ok, 1) && (ok == 1 ? receive(r, meshes) : r.str(error));
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!complete)
    throw Error("mesh generation failed: the meshing process " + ending(status) +
                " before it sent the meshes");
  if (ok != 1) throw InputError(error);
  return meshes;
}

}  // namespace emc::os
