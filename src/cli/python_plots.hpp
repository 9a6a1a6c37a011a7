#pragma once
// The figures of `depthtrack plot`, `bench` and `eval --reliability`: drawn by python/depthtrack/plots.py
// (matplotlib), run as a program.
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack::cli {

struct PlotRunner {
  std::string python;            // an interpreter that imports matplotlib
  std::filesystem::path module;  // .../depthtrack/plots.py
};

// Found before any work, so that a missing piece fails at once; what names the option or command that
// needs it in the error. The module: depthtrack/plots.py under an entry of $PYTHONPATH, else in the
// build's Python package folder, else in the installed one. The interpreter: $DEPTHTRACK_PYTHON when set,
// else the first of python3 on PATH and the build's that imports matplotlib. InputError saying what is
// missing and how to get it.
PlotRunner find_plot_runner(const std::string& what);

// Runs `python plots.py arguments...` and returns what it printed (its last line's newline removed).
// InputError with its message when it refuses its input (status 1), Error when it fails otherwise.
std::string run_plots(const PlotRunner& runner, const std::vector<std::string>& arguments);

}  // namespace depthtrack::cli
