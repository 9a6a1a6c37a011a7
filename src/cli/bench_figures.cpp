#include "cli/bench_figures.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>

#include "viz/line_plot.hpp"

namespace depthtrack::cli {

namespace {

const viz::Rgb kPalette[] = {{200, 40, 40}, {40, 90, 200}, {20, 140, 60}, {210, 120, 0}, {120, 60, 170}};

std::string upper(std::string text) {
  for (char& ch : text) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return text;
}

// One panel per value picked from a sweep's results, one series per backend, over x(result).
struct Figure {
  const char* sweep;
  const char* file;
  const char* x_label;
  std::function<double(const CaseResult&)> x;
  std::vector<std::pair<const char*, std::function<double(const CaseResult&)>>> panels;
};

bool draw(const Figure& f, const std::vector<CaseResult>& results, const std::filesystem::path& path,
          const std::function<std::filesystem::path(const std::filesystem::path&)>& place) {
  std::vector<double> xs;
  std::vector<std::string> backends;
  for (const CaseResult& r : results) {
    if (r.c.sweep != f.sweep) continue;
    if (std::find(xs.begin(), xs.end(), f.x(r)) == xs.end()) xs.push_back(f.x(r));
    if (std::find(backends.begin(), backends.end(), r.backend) == backends.end()) backends.push_back(r.backend);
  }
  if (xs.empty()) return false;
  std::sort(xs.begin(), xs.end());
  std::vector<viz::Panel> panels;
  for (const auto& [title, value] : f.panels) {
    viz::Panel panel{title, {}};
    for (size_t b = 0; b < backends.size(); ++b) {
      std::vector<double> y(xs.size(), NAN);
      for (const CaseResult& r : results)
        if (r.c.sweep == f.sweep && r.backend == backends[b])
          y[static_cast<size_t>(std::find(xs.begin(), xs.end(), f.x(r)) - xs.begin())] = value(r);
      if (std::any_of(y.begin(), y.end(), [](double v) { return std::isfinite(v); }))
        panel.series.push_back({upper(backends[b]), y, kPalette[b % std::size(kPalette)]});
    }
    if (!panel.series.empty()) panels.push_back(std::move(panel));
  }
  if (panels.empty()) return false;
  viz::plot_panels(xs, f.x_label, panels).save_png(place(path));
  return true;
}

}  // namespace

std::vector<std::filesystem::path> write_bench_figures(
    const std::vector<CaseResult>& results, const std::filesystem::path& dir,
    const std::function<std::filesystem::path(const std::filesystem::path&)>& place) {
  // Times on a log scale: the reference and a GPU differ a thousandfold, and a linear axis drew the GPUs flat.
  auto frame = [](const CaseResult& r) { return std::log10(r.frame_ms); };
  auto per_particle_us = [](const CaseResult& r) { return std::log10(1000 * r.frame_ms / r.c.particles); };
  auto memory = [](const CaseResult& r) { return r.memory_mib; };
  const Figure figures[] = {
      {"particles",
       "particles.png",
       "LOG10 PARTICLES (80X60)",
       [](const CaseResult& r) { return std::log10(r.c.particles); },
       {{"LOG10 FRAME TIME (MS)", frame}, {"LOG10 TIME PER PARTICLE (US)", per_particle_us}}},
      {"resolution",
       "resolution.png",
       "LOG10 PIXELS (80X60 TO 640X480)",
       [](const CaseResult& r) { return std::log10(static_cast<double>(r.c.width) * r.c.height); },
       {{"LOG10 FRAME TIME (MS)", frame}}},
      {"triangles",
       "triangles.png",
       "THOUSANDS OF TRIANGLES",
       [](const CaseResult& r) { return static_cast<double>(r.c.mesh->mesh.triangles.size()) / 1000; },
       {{"LOG10 FRAME TIME (MS)", frame}}},
      {"occlusion",
       "occlusion.png",
       "OCCLUSION MODE: 0 PER-PIXEL-TIME, 1 GLOBAL-TIME, 2 OFF",
       [](const CaseResult& r) { return static_cast<double>(static_cast<int>(r.c.mode)); },
       {{"LOG10 FRAME TIME (MS)", frame}, {"DEVICE MEMORY (MIB)", memory}}},
  };
  std::vector<std::filesystem::path> written;
  for (const Figure& f : figures)
    if (draw(f, results, dir / f.file, place)) written.push_back(dir / f.file);
  return written;
}

}  // namespace depthtrack::cli
