#pragma once
// How many of the filter's programs a tracker does not build on a device because their work is folded
// into another kernel there: propagate.cl where render_weigh moves a small cloud's particles
// (propagates_inside_weigh), summarize.cl where the one-launch fit summarizes in its own group
// (DeviceRefiner::summarizes_first: the one-launch layout, below the wide summary's particle count).
// For the tests that count program builds.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>

#include "compute/queue.hpp"
#include "filter/device_filter.hpp"
#include "filter/device_refiner.hpp"
#include "filter/wide_summary.hpp"

namespace depthtrack::test {

inline size_t programs_folded_away(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                   const TrackerConfig& config) {
  const compute::DeviceInfo& info = queue.info();
  const size_t pixels = static_cast<size_t>(camera.pixel_count()), particles = static_cast<size_t>(config.particles);
  const bool propagate_folded = propagates_inside_weigh(config.renderer, pixels, info.local_memory, particles);
  const bool summary_folded =
      config.refine.enabled && particles < kWideSummaryParticles &&
      resolved_refine_layout(config.refine.layout, info, mesh.triangles.size(), pixels) == RefineLayout::OneLaunch;
  return (propagate_folded ? 1 : 0) + (summary_folded ? 1 : 0);
}

}  // namespace depthtrack::test
