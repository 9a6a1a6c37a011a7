#pragma once
// How the depth residual of an estimate is spread over the image: its total variance and the part of it
// that changes from pixel to pixel (white). A sensor's noise is mostly white and averages out over the
// pixels; the mesh's, the calibration's and the working resolution's errors are smooth across the surface,
// so neighbouring pixels share them and more pixels do not average them away.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

namespace depthtrack {

struct ResidualStructure {
  int pixels = 0;    // visible pixels: a valid depth within loss.pixel_sigmas sigma(y) of the rendering
  double total = 0;  // mean of z^2 over them, z = (y - y_hat) / sigma(y)
  // Half the mean of (z_a - z_b)^2 over 4-neighbour pairs of visible pixels, at most total: the variance
  // of a residual whose neighbours are independent; a smooth residual gives about 0. 0 without a pair.
  double white = 0;
  double smooth() const { return total - white; }
};

// rendered: the mesh's depth at the estimate (0 where it covers nothing), at depth's resolution.
ResidualStructure residual_structure(std::span<const float> rendered, const ObservationModel& model,
                                     double pixel_sigmas, const DepthImage& depth);

}  // namespace depthtrack
