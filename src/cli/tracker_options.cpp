#include "cli/tracker_options.hpp"

#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <sstream>

#include "compute/backend.hpp"

namespace depthtrack::cli {

void TrackerOptions::add_to(CLI::App& command) {
  // The device selectors come from the backend registry, so a new backend appears here by itself.
  std::string selectors;
  for (const auto& backend : compute::backends()) selectors += ", " + backend.grammar;
  command.add_option("--backend", config.backend,
                     "Filter implementation: reference (sequential CPU)" + selectors +
                         " (`depthtrack info` lists devices); default: $DEPTHTRACK_DEVICE, else reference");
  renderer_option =
      command.add_option("--renderer", renderer,
                         "Who draws the pose atlas for device backends: kernel (a compute kernel on the device itself, "
                         "the fastest), gl (headless OpenGL; DEPTHTRACK_GL=egl-device|egl-surfaceless|osmesa picks the "
                         "path) or cpu (the reference rasterizer on the host)");
  renderer_option->capture_default_str();
  command.add_option("--particles", config.particles, "Number of particles")->capture_default_str();
  command
      .add_option("--resolution", resolution,
                  "Working resolution WxH; the sensor image is decimated to it by an integer factor")
      ->capture_default_str();
  command
      .add_option("--occlusion", occlusion,
                  "Occlusion model storage: per-pixel-time (p and last update time per pixel), global-time "
                  "(p only, every pixel propagated each frame) or off")
      ->capture_default_str();
  command
      .add_option("--refine", refine,
                  "on: after weighting, fit the estimate to the likelihood's maximum (damped Gauss-Newton on the "
                  "per-pixel depth residuals) and shift the particle cloud with it; off: the particle filter alone")
      ->capture_default_str();
  command.add_option("--refine-iterations", config.refine.iterations, "Gauss-Newton steps per frame of the refinement")
      ->capture_default_str();
  command.add_option("--seed", config.seed, "Random seed: the same seed gives the same particles on every backend")
      ->capture_default_str();
}

TrackerConfig TrackerOptions::resolve() const {
  TrackerConfig c = config;
  std::tie(c.width, c.height) = parse_resolution(resolution);
  c.occlusion_storage = occlusion_storage_from_string(occlusion);
  c.renderer = renderer_from_string(renderer);
  if (refine != "on" && refine != "off") throw InputError("--refine '" + refine + "' is not on or off");
  c.refine.enabled = refine == "on";
  c.validate();
  // The reference filter always draws with its own rasterizer: say so rather than ignore the choice.
  if (renderer_option && renderer_option->count() > 0 && c.resolved_backend() == "reference")
    std::fprintf(stderr,
                 "depthtrack: warning: --renderer %s has no effect with the reference backend (it draws with its own "
                 "rasterizer); it applies to the opencl and cuda backends\n",
                 renderer.c_str());
  return c;
}

std::pair<int, int> parse_resolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w <= 0 || h <= 0)
    throw InputError("resolution '" + text + "' is not of the form WxH with positive integers (e.g. 80x60)");
  return {w, h};
}

std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option) {
  std::istringstream in(text);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    try {
      size_t used = 0;
      values.push_back(std::stod(token, &used));
      if (used != token.size() || !std::isfinite(values.back())) throw std::invalid_argument(token);
    } catch (const std::exception&) {
      throw InputError(option + ": '" + token + "' is not a finite number");
    }
  }
  if (values.size() != n)
    throw InputError(option + " takes " + std::to_string(n) + " numbers, got " + std::to_string(values.size()) +
                     " in '" + text + "'");
  return values;
}

}  // namespace depthtrack::cli
