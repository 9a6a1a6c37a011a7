#include "cli/bench_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/staged_outputs.hpp"

namespace depthtrack::cli {

std::vector<std::string> figure_sweeps(const std::vector<CaseResult>& results) {
  std::vector<std::string> sweeps;
  for (const char* sweep : {"particles", "resolution", "triangles", "occlusion"})
    if (std::any_of(results.begin(), results.end(), [&](const CaseResult& r) { return r.c.sweep == sweep; }))
      sweeps.emplace_back(sweep);
  return sweeps;
}

void write_bench_cases(const std::vector<CaseResult>& results, const std::filesystem::path& path) {
  std::string text = "sweep,backend,mesh,triangles,width,height,particles,occlusion,frame_ms,memory_mib\n";
  for (const CaseResult& r : results) {
    char numbers[128];
    std::snprintf(numbers, sizeof numbers, "%.9g,", r.frame_ms);
    text += r.c.sweep + "," + r.backend + "," + r.c.mesh->name + "," + std::to_string(r.c.mesh->mesh.triangles.size()) +
            "," + std::to_string(r.c.width) + "," + std::to_string(r.c.height) + "," + std::to_string(r.c.particles) +
            "," + to_string(r.c.mode) + "," + numbers;
    if (std::isfinite(r.memory_mib)) {
      std::snprintf(numbers, sizeof numbers, "%.9g", r.memory_mib);
      text += numbers;
    }
    text += "\n";
  }
  write_text_file(path, text);
}

}  // namespace depthtrack::cli
