#include "cli/python_plots.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <vector>

extern char** environ;

namespace depthtrack::cli {

namespace fs = std::filesystem;

namespace {

// Runs a program; its exit status (127: it could not be started, 128: it was killed). Its standard output
// and error are kept in output when output is given, else dropped.
int run_program(const std::vector<std::string>& arguments, std::string* output) {
  std::vector<char*> argv;
  for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int pipe_ends[2] = {-1, -1};
  if (output && pipe(pipe_ends) != 0) return 127;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (output) {
    posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
    posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 1);
    posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 2);
    posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  } else {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  std::fflush(stdout);
  pid_t pid = 0;
  const int failed = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (output) {
    close(pipe_ends[1]);
    char buffer[4096];
    for (ssize_t n; failed == 0 && (n = read(pipe_ends[0], buffer, sizeof buffer)) != 0;) {
      if (n > 0)
        output->append(buffer, static_cast<size_t>(n));
      else if (errno != EINTR)
        break;
    }
    close(pipe_ends[0]);
  }
  if (failed != 0) return 127;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

std::vector<fs::path> module_candidates() {
  std::vector<fs::path> places;
  if (const char* path = std::getenv("PYTHONPATH")) {
    std::string entries = path;
    for (size_t start = 0; start <= entries.size();) {
      const size_t end = std::min(entries.find(':', start), entries.size());
      if (end > start) places.push_back(fs::path(entries.substr(start, end - start)) / "depthtrack" / "plots.py");
      start = end + 1;
    }
  }
#ifdef DEPTHTRACK_PYTHON_BUILD_DIR
  places.push_back(fs::path(DEPTHTRACK_PYTHON_BUILD_DIR) / "depthtrack" / "plots.py");
#endif
#ifdef DEPTHTRACK_PYTHON_INSTALL_DIR
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error)
    places.push_back(exe.parent_path().parent_path() / DEPTHTRACK_PYTHON_INSTALL_DIR / "depthtrack" / "plots.py");
#endif
  return places;
}

}  // namespace

PlotRunner find_plot_runner(const std::string& what) {
  PlotRunner runner;
  std::string looked;
  for (const fs::path& place : module_candidates()) {
    std::error_code error;
    if (fs::is_regular_file(place, error)) {
      runner.module = place;
      break;
    }
    looked += (looked.empty() ? "" : ", ") + place.string();
  }
  if (runner.module.empty())
    throw InputError(what + ": cannot find depthtrack/plots.py (looked in " +
                     (looked.empty() ? std::string("no place") : looked) +
                     "): put the folder holding depthtrack/ on PYTHONPATH");
  std::vector<std::string> interpreters;
  if (const char* chosen = std::getenv("DEPTHTRACK_PYTHON")) {
    interpreters.push_back(chosen);
  } else {
    interpreters.push_back("python3");
#ifdef DEPTHTRACK_PYTHON_EXECUTABLE
    interpreters.push_back(DEPTHTRACK_PYTHON_EXECUTABLE);
#endif
  }
  std::string tried;
  for (const std::string& python : interpreters) {
    const int status = run_program({python, "-c", "import matplotlib"}, nullptr);
    if (status == 0) {
      runner.python = python;
      return runner;
    }
    tried += (tried.empty() ? "" : "; ") + python + (status == 127 ? " was not found" : " lacks matplotlib");
  }
  throw InputError(what + " needs python3 with matplotlib (" + tried +
                   "): install it (Debian: apt install python3-matplotlib) or name an interpreter that has it in "
                   "$DEPTHTRACK_PYTHON");
}

std::string run_plots(const PlotRunner& runner, const std::vector<std::string>& arguments) {
  std::vector<std::string> command{runner.python, runner.module.string()};
  command.insert(command.end(), arguments.begin(), arguments.end());
  std::string output;
  const int status = run_program(command, &output);
  while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
  const std::string prefix = "depthtrack.plots: error: ";
  if (status == 1 && output.find(prefix) != std::string::npos)
    throw InputError(output.substr(output.find(prefix) + prefix.size()));
  if (status != 0)
    throw Error("drawing the figure failed: " + runner.python + " " + runner.module.string() + " exited with status " +
                std::to_string(status) + (output.empty() ? "" : ":\n" + output));
  return output;
}

}  // namespace depthtrack::cli
