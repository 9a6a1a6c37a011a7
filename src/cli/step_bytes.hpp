#pragma once
// Bytes each step of a device frame moves through memory, from the layout (cl/dt_state.h: 16 floats of
// state per particle; a float of atlas depth and occlusion probability, a 16-bit occlusion time index per
// particle per pixel), so `depthtrack bench` can print GB/s next to each step's time. The one place the formula
// lives. Weigh reads each particle's occlusion row from its parent (the last resampling, folded in) and
// writes its own: with an effective sample size near 1 most of those reads hit the cache, so the
// figures are upper bounds.
#include <cstddef>
#include <optional>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::cli {

struct StepBytes {
  double propagate = 0, render = 0, handoff = 0, weigh = 0, resample = 0, refine = 0;
};

// One frame of `particles` particles at `pixels` pixels each, keeping occlusion state for state_pixels
// of them (the state window's; none given: all); handoff only for the GL renderer; with inside_weigh
// (renders_inside_weigh) the tiles stay in work-group memory: no atlas written or read; with
// weigh_propagates (propagates_inside_weigh) the motion step's state read and write are weigh's.
StepBytes step_bytes(size_t particles, size_t pixels, OcclusionStorage mode, bool gl_handoff, int refine_iterations,
                     bool inside_weigh = false, std::optional<size_t> state_pixels = std::nullopt,
                     bool weigh_propagates = false);

// Device memory the filter's buffers take without GL pages, MiB (device_filter_bytes_per_particle), with
// an atlas of atlas_tiles tiles (none given: every particle's; 0 where it is drawn inside weigh;
// kernel_atlas_tiles where it is drawn in turns) and the state window's rows as it needs them: an
// automatic window's buffers hold room for up to half as many again (StateRows, filter/state_rows.cpp),
// which this leaves out.
double filter_memory_mib(size_t particles, size_t pixels, OcclusionStorage mode,
                         std::optional<size_t> atlas_tiles = std::nullopt,
                         std::optional<size_t> state_pixels = std::nullopt);

}  // namespace depthtrack::cli
