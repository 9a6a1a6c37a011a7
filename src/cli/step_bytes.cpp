#include "cli/step_bytes.hpp"

#include <utility>

#include "dt_state.h"
#include "filter/device_filter.hpp"

namespace depthtrack::cli {

StepBytes step_bytes(size_t particles, size_t pixels, OcclusionStorage mode, bool gl_handoff, int refine_iterations,
                     bool inside_weigh, std::optional<size_t> state_pixels, bool weigh_propagates) {
  const double n = static_cast<double>(particles), px = static_cast<double>(pixels), f = sizeof(float);
  const double kept = static_cast<double>(state_pixels.value_or(pixels));       // the state window's
  const double state = DT_STATE_STRIDE * f;                                      // per particle
  const double occlusion = mode == OcclusionStorage::Off ? 0 : kept * f;         // p per pixel
  const double times = mode == OcclusionStorage::PerPixelTime ? kept * 2 : 0.0;  // t_last's 16-bit frame index
  StepBytes b;
  b.propagate = n * 2 * state;                                // read and write each state
  const double atlas = inside_weigh ? 0 : px * f;             // a tile's depths through memory
  b.render = n * atlas;                                       // written
  b.handoff = gl_handoff ? n * px * f * 2 : 0;                // GL's page read, atlas written
  b.weigh = n * (atlas + 2 * occlusion + 2 * times + 3 * f);  // atlas, parent's row read, own row written
  b.resample = n * (2 * state + 3 * f);                       // the kinematic gather (weigh gathers the rows)
  b.refine = refine_iterations * 3 * px * f;                  // one pose: its tile, depth, ids
  if (weigh_propagates) b.weigh += std::exchange(b.propagate, 0.0);
  return b;
}

double filter_memory_mib(size_t particles, size_t pixels, OcclusionStorage mode, std::optional<size_t> atlas_tiles,
                         std::optional<size_t> state_pixels) {
  const double tiles = static_cast<double>(atlas_tiles.value_or(particles));
  return (device_filter_bytes_per_particle(pixels, mode, false, false, state_pixels) * static_cast<double>(particles) +
          tiles * static_cast<double>(pixels) * sizeof(float)) /
         (1 << 20);
}

}  // namespace depthtrack::cli
