// Output/plot: tools/plot_monitors.py as a child process (posix_spawn, an argument vector).
#include "emcontact/app/plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <vector>

extern char** environ;

namespace emc::app {
namespace {

/// A path the script cannot take for an option: "-x/monitors.csv" -> "./-x/monitors.csv".
std::string operand(const std::string& path) {
  return path[0] == '-' ? "./" + path : path;
}

/// Spawns argv[0] with stdout and stderr to /dev/null; its exit status, or -1.
int spawn_and_wait(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

void plot_monitors(const std::string& dir) {
  const std::string python = "/usr/bin/python3", script = EMC_PLOT_SCRIPT;
  const std::string csv = operand(dir + "/monitors.csv");
  if (spawn_and_wait({python, script, csv, "--out", operand(dir + "/energies.png")}) != 0)
    std::fprintf(stderr, "warning: could not plot %s with %s %s (it needs matplotlib)\n",
                 csv.c_str(), python.c_str(), script.c_str());
}

}  // namespace emc::app
