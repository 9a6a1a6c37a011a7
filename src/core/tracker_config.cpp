#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker_config.hpp>
#include <sstream>
#include <string>

#include "core/image_limits.hpp"

namespace depthtrack {

const char* to_string(OcclusionStorage mode) {
  switch (mode) {
    case OcclusionStorage::PerPixelTime:
      return "per-pixel-time";
    case OcclusionStorage::GlobalTime:
      return "global-time";
    case OcclusionStorage::Off:
      return "off";
  }
  return "?";
}

OcclusionStorage occlusion_storage_from_string(const std::string& name) {
  for (auto mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime, OcclusionStorage::Off})
    if (name == to_string(mode)) return mode;
  throw InputError("unknown occlusion mode '" + name + "' (choose per-pixel-time, global-time or off)");
}

const char* to_string(Renderer renderer) {
  switch (renderer) {
    case Renderer::Kernel:
      return "kernel";
    case Renderer::Gl:
      return "gl";
    case Renderer::Cpu:
      return "cpu";
  }
  return "?";
}

Renderer renderer_from_string(const std::string& name) {
  for (auto renderer : {Renderer::Kernel, Renderer::Gl, Renderer::Cpu})
    if (name == to_string(renderer)) return renderer;
  throw InputError("unknown renderer '" + name + "' (choose cpu, gl or kernel)");
}

OcclusionWindow occlusion_window_from_string(const std::string& text) {
  if (text == "auto") return OcclusionWindow{};
  if (text == "full") return OcclusionWindow::whole_image();
  int width = 0, height = 0;
  char x = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || (x != 'x' && x != 'X') || (in >> extra) || width <= 0 || height <= 0)
    throw InputError("occlusion window '" + text + "' is not auto, full or WxH with positive integers");
  return OcclusionWindow::fixed(width, height);
}

const char* to_string(RefineLayout layout) {
  switch (layout) {
    case RefineLayout::Auto:
      return "auto";
    case RefineLayout::OneGroup:
      return "one-group";
    case RefineLayout::Spread:
      return "spread";
    case RefineLayout::OneLaunch:
      return "one-launch";
  }
  return "?";
}

RefineLayout refine_layout_from_string(const std::string& name) {
  for (auto layout : {RefineLayout::Auto, RefineLayout::OneGroup, RefineLayout::Spread, RefineLayout::OneLaunch})
    if (name == to_string(layout)) return layout;
  throw InputError("unknown refinement layout '" + name + "' (choose auto, one-group, spread or one-launch)");
}

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("invalid tracker configuration: " + what);
}
bool positive(double v) {
  return std::isfinite(v) && v > 0;
}
bool probability(double v) {
  return std::isfinite(v) && v >= 0 && v <= 1;
}
}  // namespace

std::string TrackerConfig::resolved_backend() const {
  return backend.empty() ? "reference" : backend;
}

void TrackerConfig::validate() const {
  require(particles > 0, "particle count " + std::to_string(particles) + " must be at least 1");
  require(std::isfinite(budget_ms) && budget_ms >= 0, "frame budget must be finite and >= 0 ms (0: off)");
  require(min_particles >= 1 && (budget_ms == 0 || min_particles <= particles),
          "min particles " + std::to_string(min_particles) +
              " must be in [1, particles = " + std::to_string(particles) + "]");
  require(atlas_particles >= 0,
          "atlas particles " + std::to_string(atlas_particles) + " must not be negative (0: as many as fit)");
  require(std::isfinite(simplify_error) && simplify_error >= 0 && simplify_error <= 1,
          "mesh simplification error must be in [0, 1] metres (0: the mesh as given)");
  require(width > 0 && height > 0, "working resolution must be positive");
  require(width <= kMaxImageSide && height <= kMaxImageSide && static_cast<int64_t>(width) * height <= kMaxImagePixels,
          "working resolution " + std::to_string(width) + "x" + std::to_string(height) + " is larger than the " +
              std::to_string(kMaxImageSide) + " pixels a side and " + std::to_string(kMaxImagePixels) +
              " pixels in all allowed");
  require(occlusion_window.width >= 0 && occlusion_window.height >= 0,
          "occlusion window " + std::to_string(occlusion_window.width) + "x" + std::to_string(occlusion_window.height) +
              " must not be negative (0: the whole image)");
  require(positive(observation.sigma_constant) && std::isfinite(observation.sigma_quadratic) &&
              observation.sigma_quadratic >= 0,
          "depth noise sigma must be positive");
  require(probability(observation.tail_weight) && observation.tail_weight < 1, "tail weight must be in [0, 1)");
  require(positive(observation.max_depth) && observation.max_depth <= 1000, "max depth must be in (0, 1000] metres");
  require(positive(observation.occluder_rate), "occluder rate must be positive");
  require(probability(occlusion.p_occluded_stays) && probability(occlusion.p_visible_to_occluded) &&
              occlusion.p_occluded_stays > occlusion.p_visible_to_occluded && occlusion.p_occluded_stays < 1,
          "occlusion transition probabilities need 0 <= b < a < 1");
  require(probability(occlusion.initial), "initial occlusion probability must be in [0, 1]");
  require(gl_path == "auto" || gl_path == "egl-device" || gl_path == "egl-surfaceless" || gl_path == "osmesa",
          "GL path '" + gl_path + "' is not auto, egl-device, egl-surfaceless or osmesa");
  require(std::isfinite(motion.damping) && motion.damping > 0 && motion.damping < 1, "damping must be in (0, 1)");
  require(std::isfinite(motion.sigma_linear) && motion.sigma_linear >= 0, "linear motion noise must be >= 0");
  require(std::isfinite(motion.sigma_angular) && motion.sigma_angular >= 0, "angular motion noise must be >= 0");
  require(positive(motion.reference_rate), "motion reference rate must be positive");
  require(std::isfinite(resample_kl_threshold) && resample_kl_threshold >= 0, "resampling threshold must be >= 0");
  require(renderer == Renderer::Cpu || renderer == Renderer::Gl || renderer == Renderer::Kernel,
          "renderer " + std::to_string(static_cast<int>(renderer)) + " is not cpu, gl or kernel");
  require(refine.iterations >= 0 && refine.iterations <= 100, "refine iterations must be in [0, 100]");
  require(std::isfinite(refine.damping) && refine.damping >= 0, "refine damping must be >= 0");
  require(std::isfinite(refine.converged_motion) && refine.converged_motion >= 0,
          "refine converged motion must be >= 0 metres");
  require(probability(refine.min_incidence) && refine.min_incidence < 1, "refine min incidence must be in [0, 1)");
  require(positive(refine.noise_scale) && refine.noise_scale <= 10, "refine noise scale must be in (0, 10]");
  require(refine.fine_noise_scale == 0 || (positive(refine.fine_noise_scale) && refine.fine_noise_scale <= 10),
          "refine fine noise scale must be 0 (no second stage) or in (0, 10]");
  require(refine.layout == RefineLayout::Auto || refine.layout == RefineLayout::OneGroup ||
              refine.layout == RefineLayout::Spread || refine.layout == RefineLayout::OneLaunch,
          "refine layout must be auto, one-group, spread or one-launch");
  require(positive(near_plane) && near_plane < observation.max_depth, "near plane must be in (0, max depth)");
  require(positive(max_time_step), "max time step must be positive");
  require(positive(loss.pixel_sigmas), "loss pixel_sigmas must be positive");
  require(probability(loss.lost_below) && probability(loss.found_above) && loss.lost_below <= loss.found_above,
          "loss thresholds need 0 <= lost_below <= found_above <= 1");
  require(probability(loss.found_outline), "loss found_outline must be in [0, 1]");
  require(loss.search_after >= 1, "loss search_after must be at least 1 frame");
  require(std::isfinite(recovery.budget_ms) && recovery.budget_ms > 0, "recovery budget must be positive (ms)");
}

}  // namespace depthtrack
