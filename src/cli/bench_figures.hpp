#pragma once
// The figures of `depthtrack bench` (thesis chapter 6), drawn with the project's line plots: frame time
// against particles, resolution and triangles, and time and device memory per occlusion mode; one line
// per backend.
#include <filesystem>
#include <functional>
#include <vector>

#include "cli/bench_suite.hpp"

namespace depthtrack::cli {

// Writes particles.png, resolution.png, triangles.png and occlusion.png into dir (a figure whose sweep
// has no results is left out); returns the files written. place(file) says where to write file (a
// partial file the caller renames once all are written).
std::vector<std::filesystem::path> write_bench_figures(
    const std::vector<CaseResult>& results, const std::filesystem::path& dir,
    const std::function<std::filesystem::path(const std::filesystem::path&)>& place);

}  // namespace depthtrack::cli
