#include "filter/state_rows.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>
#include <sstream>
#include <utility>

namespace depthtrack {

StateRows::StateRows(compute::Queue& queue, const TrackerConfig& config, const Camera& camera, const FramePlan& plan,
                     const model::StateWindow& window)
    : queue_(queue),
      config_(config),
      camera_(camera),
      count_(plan.particles),
      pixels_(plan.pixels),
      atlas_tiles_(plan.atlas_tiles) {
  check(window);
  pixel_limit_ = compute_pixel_limit();
}

double StateRows::bytes_per_particle(size_t state_pixels) const {
  // GL's pages sit on the same GPU; the kernel renderer's atlas is counted apart (atlas_bytes).
  return device_filter_bytes_per_particle(pixels_, config_.occlusion_storage,
                                          config_.renderer == Renderer::Gl && queue_.info().is_gpu,
                                          config_.renderer != Renderer::Kernel, state_pixels);
}

// The kernel renderer's atlas (FramePlan::atlas_tiles); the other renderers' is counted per particle.
double StateRows::atlas_bytes() const {
  if (config_.renderer != Renderer::Kernel) return 0;
  return static_cast<double>(atlas_tiles_) * static_cast<double>(pixels_) * sizeof(float);
}

void StateRows::check(const model::StateWindow& window) const {
  const double per_particle = bytes_per_particle(window.pixels()), atlas = atlas_bytes();
  const double needed = per_particle * static_cast<double>(config_.particles) + atlas;
  const auto& info = queue_.info();
  if (info.global_memory > 0 && needed > 0.9 * static_cast<double>(info.global_memory)) {
    std::ostringstream m;
    m.precision(3);
    m << model::particles_and_window(config_, camera_, window) << " need " << needed / (1 << 30)
      << " GiB of device memory but " << info.name << " has " << static_cast<double>(info.global_memory) / (1 << 30)
      << " GiB; at most about "
      << static_cast<long long>(std::max(0.0, 0.9 * static_cast<double>(info.global_memory) - atlas) / per_particle)
      << " particles fit" << (atlas > 0 ? " beside the atlas (TrackerConfig::atlas_particles makes it smaller)" : "");
    throw InputError(m.str());
  }
}

// The most state pixels a particle's rows may grow to in 90 % of the device's memory (0: unknown).
size_t StateRows::compute_pixel_limit() const {
  const double memory = static_cast<double>(queue_.info().global_memory);
  const double per_pixel = bytes_per_particle(1) - bytes_per_particle(0);
  if (!(memory > 0) || per_pixel == 0) return 0;
  const double share = (0.9 * memory - atlas_bytes()) / static_cast<double>(count_) - bytes_per_particle(0);
  return share < per_pixel ? 1 : static_cast<size_t>(share / per_pixel);
}

// Rows for `window` in a pair of state buffers (probabilities, times), reallocated only when they hold
// fewer: an automatic window's rows are sized at the start and grow with it. Kernels always take both
// buffers, so a mode that keeps no such state gets the placeholder (one element; two 16-bit ones).
void StateRows::reserve(compute::Buffer<float>& probabilities, compute::Buffer<uint16_t>& times,
                        const model::StateWindow& window) {
  const size_t kept = count_ * window.pixels();
  // An automatic window grows by a pixel or two a frame while the estimate settles or the object
  // nears, so its rows take half as much again (within the memory's bound), at the start as when
  // outgrown, rather than being reallocated every few frames: a reallocation's free waits for the
  // device, that is for every object's work queued on it, and changes the frame's graph. A fixed
  // window never grows: its rows are what it needs.
  const auto rows = [&](size_t placeholder) {
    if (!config_.occlusion_window.is_automatic()) return std::max(kept, placeholder);
    const size_t roomy = kept + kept / 2, limit = pixel_limit_ * count_;
    return std::max({kept, placeholder, limit > 0 ? std::min(roomy, limit) : roomy});
  };
  const bool kept_probabilities = config_.occlusion_storage != OcclusionStorage::Off;
  const bool indices = config_.occlusion_storage == OcclusionStorage::PerPixelTime;
  if (kept_probabilities ? probabilities.size() < std::max<size_t>(kept, 1) : probabilities.size() < 1) {
    probabilities = compute::Buffer<float>(queue_, kept_probabilities ? rows(1) : 1);
    ++allocations_;
  }
  if (indices ? times.size() < std::max<size_t>(kept, 2) : times.size() < 2) {
    times = compute::Buffer<uint16_t>(queue_, indices ? rows(2) : 2);
    ++allocations_;
  }
}

void StateRows::swap() {
  std::swap(occlusion, scratch_occlusion);
  std::swap(time, scratch_time);
}

}  // namespace depthtrack
