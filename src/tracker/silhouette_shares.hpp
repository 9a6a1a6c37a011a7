#pragma once
// How the depth explains a pose's rendered silhouette (PoseEvidence): shares that mean the same for any
// object and resolution, from which the tracker's confidence is built (tracker/confidence_model.hpp).
#include <cstddef>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/pose_evidence.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

#include "reference/rasterizer.hpp"

namespace depthtrack {

// Visible pixels needed for PoseEvidence::plane_rms: fewer leave it at visible_rms. A plane through a
// few pixels (the synthetic handset behind a 90 % occluder shows 5-9 at 80x60) fits a wrong pose's
// strips as readily as a right one's.
inline constexpr size_t kPlanePixels = 16;

// The evidence (PoseEvidence), with the outline's size the shares are taken over.
struct SilhouetteShares : PoseEvidence {
  int outline = 0;  // the outline's outer neighbours counted (each once per covered neighbour)
};

SilhouetteShares silhouette_shares(const reference::Rasterizer& rasterizer, const ObservationModel& model,
                                   double pixel_sigmas, const Pose& pose, const DepthImage& depth,
                                   std::span<float> scratch);
// The same from a rendering already drawn (depth's size; 0 where the mesh covers nothing) whose covered
// pixels lie in box.
SilhouetteShares silhouette_shares(std::span<const float> rendered, const reference::PixelBox& box,
                                   const ObservationModel& model, double pixel_sigmas, const DepthImage& depth);

}  // namespace depthtrack
