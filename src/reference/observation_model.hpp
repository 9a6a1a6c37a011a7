#pragma once
// The per-pixel observation model of MODEL.md, in double precision: the oracle for the kernels.
#include <cmath>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::reference {

struct PixelDensities {
  double visible;     // p_vis(y | y_hat): the object is seen at this pixel
  double occluded;    // p_occ(y | y_hat): something in front of the object is seen
  double background;  // p_bg(y): no object at this pixel
  // The three are stored divided by exp(log_scale), so that they stay finite at any depth (0 within a
  // sensor's range): their ratios, the log ratio and the posterior do not depend on it.
  double log_scale = 0;
};

// Depth noise sigma(y) grows with the observed depth y.
double depth_sigma(const ObservationModel& m, double y);

// Where a valid depth y lies against the surface at y_hat, within pixel_sigmas sigma(y): the
// confidence's visible pixels are Within (silhouette_shares; the refinement counts them too).
enum class BandSide { Nearer, Within, Behind };
BandSide band_side(const ObservationModel& m, double pixel_sigmas, double y, double y_hat);

// Densities of observing depth y where the particle renders depth y_hat (both metres, > 0).
PixelDensities pixel_densities(const ObservationModel& m, double y, double y_hat);

// What pixel_densities computes from the observed depth y alone, the same for every particle of a
// frame: computed once, it spares each particle two exponentials at that pixel. The densities from it
// are pixel_densities' own (pixel_densities is computed through it).
struct ObservedDepth {
  double y, sigma;
  double gaussian_norm;  // sqrt(2 pi) sigma
  double erfc_shift;     // lambda sigma^2
  double erfc_width;     // sqrt(2) sigma
  double scale;          // exp(-log_scale)
  double log_scale;      // max(0, exponent)
  double tail_scaled;    // the tail's density times scale
  double background;     // the occluder prior's density without the object, times scale
};
ObservedDepth observed_depth(const ObservationModel& m, double y);
// Inline, as the two below: every pixel of every particle's drawing calls them.
inline PixelDensities pixel_densities(const ObservationModel& m, const ObservedDepth& o, double y_hat) {
  const double tail = m.tail_weight / m.max_depth;
  const double keep = 1.0 - m.tail_weight;
  const double lambda = m.occluder_rate;
  const double z = (o.y - y_hat) / o.sigma;
  const double gaussian = std::exp(-0.5 * z * z) / o.gaussian_norm;
  // The same prior on [0, y_hat]: the background's times the part of it in front of y_hat,
  // erfc(-x) / (2 (1 - exp(-lambda y_hat))), which no longer overflows.
  const double in_front =
      std::erfc(-(y_hat - o.y + o.erfc_shift) / o.erfc_width) / (-2.0 * std::expm1(-lambda * y_hat));
  return {(tail + keep * gaussian) * o.scale, o.tail_scaled + o.background * in_front, o.tail_scaled + o.background,
          o.log_scale};
}

// One pixel's term of a particle's log-likelihood: log(((1-p) p_vis + p p_occ) / p_bg), where p
// is the pixel's occlusion probability propagated to now.
inline double pixel_log_ratio(const PixelDensities& d, double p) {
  return std::log(((1.0 - p) * d.visible + p * d.occluded) / d.background);
}

// Bayes update of the occlusion probability after the observation: p p_occ / ((1-p) p_vis + p p_occ).
inline double occlusion_posterior(const PixelDensities& d, double p) {
  return p * d.occluded / ((1.0 - p) * d.visible + p * d.occluded);
}

}  // namespace depthtrack::reference
