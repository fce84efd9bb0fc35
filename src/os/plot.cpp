// Output/plot: tools/plot_monitors.py as a child process (posix_spawn, an argument vector).
#include "emcontact/os/plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/atomic_file.hpp"

extern char** environ;

namespace emc::os {
namespace {

/// The child's descriptor of monitors.csv.
constexpr int kCsvFd = 3;

/// The last non-empty line of what was written to `fd` (cut at 200 characters), or "".
std::string last_line(int fd) {
  std::string text;
  std::array<char, 4096> chunk;
  if (::lseek(fd, 0, SEEK_SET) != 0) return "";
  for (ssize_t n; (n = ::read(fd, chunk.data(), chunk.size())) > 0;) {
    text.append(chunk.data(), static_cast<std::size_t>(n));
    if (text.size() > (1u << 20)) text.erase(0, text.size() - 4096);  // only the end matters
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const std::size_t nl = text.find_last_of('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

/// A copy of `fd` numbered above the child's descriptors (closed on exec), so that moving the
/// copies to 2 and kCsvFd never overwrites one that is still to be moved.
struct HighFd {
  int fd;
  explicit HighFd(int from) : fd(::fcntl(from, F_DUPFD_CLOEXEC, 10)) {}
  ~HighFd() {
    if (fd >= 0) ::close(fd);
  }
  HighFd(const HighFd&) = delete;
  HighFd& operator=(const HighFd&) = delete;
};

/// Spawns `args` in the directory `dir` (its descriptor: fchdir) with stdin and stdout on
/// /dev/null, stderr into `err` and `csv` as descriptor kCsvFd; "" if it exited 0, else why not.
std::string spawn_and_wait(std::vector<std::string> args, const output::Directory& dir, int csv,
                           int err) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const HighFd c(csv), e(err), d(dir.fd());
  if (c.fd < 0 || e.fd < 0 || d.fd < 0) return std::string("dup: ") + std::strerror(errno);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, e.fd, 2);
  posix_spawn_file_actions_adddup2(&fa, c.fd, kCsvFd);
  posix_spawn_file_actions_addfchdir_np(&fa, d.fd);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return std::string("cannot run ") + argv[0] + ": " + std::strerror(rc);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      return std::string("cannot wait for ") + argv[0] + ": " + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  std::string line = last_line(err);
  if (!line.empty()) return line;
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  return "exit status " + std::to_string(WEXITSTATUS(status));
}

/// Whether `name` in `dir` is still the file open as `fd`.
bool same_file(const output::Directory& dir, const std::string& name, int fd) {
  struct stat a {
  }, b{};
  return ::fstatat(dir.fd(), name.c_str(), &a, AT_SYMLINK_NOFOLLOW) == 0 && ::fstat(fd, &b) == 0 &&
         a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// Plots into a fresh temporary of `dir` (named *.png: matplotlib picks the format by it), then
/// renames it to energies.png; "" or why not.
std::string plot(const output::Directory& dir, const std::string& python,
                 const std::string& script) {
  const int csv = ::openat(dir.fd(), "monitors.csv", O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (csv < 0) return dir.path("monitors.csv") + ": " + std::strerror(errno);
  const int err = ::memfd_create("emcontact-plot-stderr", MFD_CLOEXEC);
  if (err < 0) {
    ::close(csv);
    return std::string("cannot capture the plot's messages: ") + std::strerror(errno);
  }
  std::string why;
  try {
    output::TempFile png = output::create_temp(dir, "energies.png", ".png");
    why = spawn_and_wait({python, script, "/proc/self/fd/" + std::to_string(kCsvFd), "--out",
                          png.name, "--title", dir.path("monitors.csv")},
                         dir, csv, err);
    if (why.empty() && !same_file(dir, png.name, png.fd))
      why = dir.path(png.name) + " was replaced while the plot wrote it";
    if (why.empty())
      output::commit_temp(dir, png, "energies.png");
    else
      output::discard_temp(dir, png);
  } catch (const Error& e) {
    why = e.what();
  }
  ::close(err);
  ::close(csv);
  return why;
}

/// The plot script: the one installed beside the binary (EMC_PLOT_SCRIPT_INSTALLED, relative to
/// the binary's directory: <prefix>/share/emcontact/ after `cmake --install`), else the source
/// tree's (EMC_PLOT_SCRIPT, for the binary of a build tree).
std::string plot_script() {
  std::string self(4096, '\0');
  ssize_t n;
  while ((n = ::readlink("/proc/self/exe", self.data(), self.size())) >= 0 &&
         static_cast<std::size_t>(n) == self.size())  // it may have been cut: a larger one
    self.resize(2 * self.size());
  if (n > 0) {
    self.resize(static_cast<std::size_t>(n));
    const std::string installed = self.substr(0, self.rfind('/') + 1) + EMC_PLOT_SCRIPT_INSTALLED;
    if (char* real = ::realpath(installed.c_str(), nullptr)) {  // without bin/..
      std::string script = real;
      std::free(real);
      if (::access(script.c_str(), R_OK) == 0) return script;
    }
  }
  return EMC_PLOT_SCRIPT;
}

}  // namespace

void plot_monitors(const output::Directory& dir) {
  const std::string python = "/usr/bin/python3", script = plot_script();
  const std::string why = plot(dir, python, script);
  if (!why.empty())
    std::fprintf(stderr, "warning: could not plot %s with %s %s: %s\n",
                 dir.path("monitors.csv").c_str(), python.c_str(), script.c_str(), why.c_str());
}

}  // namespace emc::os
