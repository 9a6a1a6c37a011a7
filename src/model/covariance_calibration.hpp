#pragma once
// The reported covariance from the fit's: the fit's H counts every pixel as independent at the filter's
// sigma(y), which is wide on purpose, so alone it is far too wide for a clean sensor and far too narrow
// where the residual is smooth (a mesh, a calibration or a working resolution that is off shifts whole
// patches of pixels together). The residual's own size and structure set the scale instead: its white
// part (sensor noise, independent from pixel to pixel) averages over the pixels as the fit assumes; its
// smooth part is shared by neighbours, so the pixels carry it as kSmoothPatches independent patches only.
#include <Eigen/Core>

namespace depthtrack::model {

// How many independent pieces a smooth residual over the whole silhouette counts as, and how much the
// white part's variance is taken up by (the neighbour differences miss what neighbours share of it). Both
// chosen on the synthetic sequences and ycbv-0000 so that about 95 % of the frames' errors lie in the
// 95 % region, then checked on ycbv-0049 and the castle: docs/user/troubleshooting.md, "How far the
// covariance holds", has the coverage per sequence.
constexpr double kSmoothPatches = 2.0;
constexpr double kWhiteScale = 1.5;
// The least variance (in sigma(y)^2) the residual is taken to have: a residual of exactly 0 (a rendered
// image tracked with its own mesh) would otherwise claim a pose known exactly.
constexpr double kMinResidualVariance = 1e-4;

// fit: the fit's covariance (model::fit_covariance) at the filter's sigma(y). white and smooth: the
// residual's variance in sigma(y)^2, split as ResidualStructure; pixels: the visible pixels it is over.
// Returns fit times kWhiteScale white + smooth max(1, pixels / kSmoothPatches), that factor at least
// kMinResidualVariance; +infinity on the diagonal (undetermined axes) and NaN stay.
Eigen::Matrix<double, 6, 6> calibrated_covariance(const Eigen::Matrix<double, 6, 6>& fit, double white, double smooth,
                                                  int pixels);

}  // namespace depthtrack::model
