#pragma once
// `depthtrack eval --reliability`: the diagram is drawn by python/depthtrack/plots.py (matplotlib), run
// as a program on the frames CSV.
#include <filesystem>
#include <string>

namespace depthtrack::cli {

struct PlotRunner {
  std::string python;            // an interpreter that imports matplotlib
  std::filesystem::path module;  // .../depthtrack/plots.py
};

// Found before any tracking, so that a missing piece fails at once. The module: depthtrack/plots.py under
// an entry of $PYTHONPATH, else in the build's Python package folder, else in the installed one. The
// interpreter: $DEPTHTRACK_PYTHON when set, else the first of python3 on PATH and the build's that imports
// matplotlib. InputError saying what is missing and how to get it.
PlotRunner find_plot_runner();

// Runs `python plots.py reliability CSV PNG`; Error when it fails (its own message is on stderr).
void draw_reliability(const PlotRunner& runner, const std::filesystem::path& csv, const std::filesystem::path& png);

}  // namespace depthtrack::cli
