#pragma once
// The figures of `depthtrack bench` (thesis chapter 6): the cases' outcomes as cases.csv, drawn by
// depthtrack/plots.py (matplotlib): frame time against particles, resolution and triangles, and time and
// device memory per occlusion mode; a line (or bar) per backend, times on log axes in ms.
#include <filesystem>
#include <string>
#include <vector>

#include "cli/bench_suite.hpp"

namespace depthtrack::cli {

// The sweeps drawn as figures (particles, resolution, triangles, occlusion) that have a case in results,
// in that order; the figure of sweep S is S.png.
std::vector<std::string> figure_sweeps(const std::vector<CaseResult>& results);

// Writes results as CSV to path: sweep,backend,mesh,triangles,width,height,particles,occlusion,frame_ms,
// memory_mib (empty where the backend has no device memory), a row per case run. Error naming the file
// when it cannot be written.
void write_bench_cases(const std::vector<CaseResult>& results, const std::filesystem::path& path);

}  // namespace depthtrack::cli
