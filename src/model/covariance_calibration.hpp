#pragma once
// The reported covariance from the fit's: the fit's H counts every pixel as independent at the filter's
// sigma(y), which is wide on purpose, so alone it is far too wide for a clean sensor and far too narrow
// where the residual is smooth (a mesh, a calibration or a working resolution that is off shifts whole
// patches of pixels together). The residual's own size and structure set the scale instead: its white
// part (sensor noise, independent from pixel to pixel) averages over the pixels as the fit assumes; its
// smooth part is shared by neighbours, so the pixels carry it as kSmoothPatches independent patches only.
// What the residual cannot show is added or set apart here too: the camera's principal point, known to
// half a pixel, moves the pose sideways without changing its depth; a turn about an axis of symmetry
// changes the depth little or not at all; a pose that barely any of the depth supports is not determined.
#include <Eigen/Core>

namespace depthtrack::model {

// How many independent pieces a smooth residual over the whole silhouette counts as, and how much the
// white part's variance is taken up by (the neighbour differences miss what neighbours share of it). Both
// chosen on the synthetic sequences and the two YCB-Video clips at 80x60 and 160x120 so that 90-99 % of
// the frames' errors lie in the 95 % region, then checked on the castle: docs/covariance.md has the
// coverage per sequence.
constexpr double kSmoothPatches = 1.75;
constexpr double kWhiteScale = 1.0;
// The working width the two constants hold at; at a width w the scale is times sqrt(kReferenceWidth / w):
// a finer working resolution's errors shrink faster than its pixel count says (at 160x120 the errors needed
// about 0.7 of the 80x60 scale on every synthetic sequence and clip).
constexpr double kReferenceWidth = 80.0;
// The least variance (in sigma(y)^2) the residual is taken to have: a residual of exactly 0 (a rendered
// image tracked with its own mesh) would otherwise claim a pose known exactly.
constexpr double kMinResidualVariance = 1e-4;
// The principal point's uncertainty in the sensor's pixels (the two conventions for where a pixel's centre
// lies differ by half a pixel): the pose's centre moves sideways by that times depth / focal length.
constexpr double kPrincipalPointPixels = 0.5;
// The variance given to a direction the depth cannot determine that is not one coordinate axis (a turn
// about a tilted axis of symmetry), in rad^2 (m^2): far beyond any error a determined direction reports.
constexpr double kUndeterminedVariance = 1e2;
// A direction of the finite block with a variance at least this (rad^2 or m^2) is undetermined: count the
// degrees of freedom and the region over the others only (eval's check_covariance does).
constexpr double kDeterminedBelow = 1.0;
// Below this share of the silhouette's measured pixels agreeing with the pose (PoseEvidence::visible), the
// depth supports too little of the object to determine the pose: the covariance says so (no axis determined).
constexpr double kLeastVisibleShare = 0.25;

// fit: the fit's covariance (model::fit_covariance) at the filter's sigma(y). white and smooth: the
// residual's variance in sigma(y)^2, split as ResidualStructure; pixels: the visible pixels it is over;
// width: the working resolution's. Returns fit times (kWhiteScale white + smooth max(1, pixels /
// kSmoothPatches)) sqrt(kReferenceWidth / width), that factor at least kMinResidualVariance; +infinity on
// the diagonal (undetermined axes) and NaN stay.
Eigen::Matrix<double, 6, 6> calibrated_covariance(const Eigen::Matrix<double, 6, 6>& fit, double white, double smooth,
                                                  int pixels, int width);

// covariance with the principal point's sideways shift added to the centre's x and y variances:
// (kPrincipalPointPixels depth / focal)^2, depth the centre's (m), focal the sensor's (pixels). Set-apart
// (+infinity) and NaN entries stay.
Eigen::Matrix<double, 6, 6> with_principal_point(const Eigen::Matrix<double, 6, 6>& covariance, double depth,
                                                 double focal);

// covariance with the error along direction (a twist about the centre, as the covariance's axes) left
// undetermined: kUndeterminedVariance along its part in the finite (determined) axes, normalized. A
// direction whose finite part is under a tenth of its length already lies in the set-apart axes: then
// covariance is returned as it is.
Eigen::Matrix<double, 6, 6> with_undetermined_direction(const Eigen::Matrix<double, 6, 6>& covariance,
                                                        const Eigen::Matrix<double, 6, 1>& direction);

// No axis determined: +infinity on the diagonal, 0 elsewhere.
Eigen::Matrix<double, 6, 6> undetermined_covariance();

}  // namespace depthtrack::model
