#pragma once
// A mesh's axis of (near) rotational symmetry: a can, a bowl, a mug but for its handle. Turning such an
// object about that axis changes its depth image little or not at all, so the depth cannot tell the turn
// (the reported covariance leaves it undetermined).
//
// How: the axis is fitted to the surface's normals, which all meet the axis of a body of revolution
// (a . (n x (x - p)) = 0 for axis direction a through p, every surface point x with normal n), by
// weighted least squares that down-weights the parts that break the symmetry (a handle); then the
// surface, sampled by area, is turned about the fitted axis by several angles, and the share of it that
// lands within kSymmetryTolerance of the diameter of the untouched surface is measured. The mesh is
// near-symmetric where the least of those shares is at least kSymmetricShare.
#include <Eigen/Core>
#include <depthtrack/mesh.hpp>
#include <optional>

namespace depthtrack {

// A turned surface point counts as on the surface within this share of the mesh's bounding-box diagonal.
constexpr double kSymmetryTolerance = 0.01;
// The least share of the surface (by area) that every tested turn maps onto the surface. The YCB meshes:
// tuna can and bowl 1.00, mug 0.91 (its handle 9 % of the area); every box, the mustard bottle, the
// potted-meat can and the dbot handset 0.53 or less.
constexpr double kSymmetricShare = 0.8;

struct SymmetryAxis {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       // a point on the axis (object frame, metres)
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit
  double share = 0;                                      // the least share the turns mapped onto the surface
};

// The fitted axis and its share, whether or not the mesh is near-symmetric (nullopt only for a mesh
// with no triangle of positive area).
std::optional<SymmetryAxis> fit_symmetry_axis(const Mesh& mesh);

// The axis where the mesh is near-symmetric about it (share at least kSymmetricShare), else nullopt.
std::optional<SymmetryAxis> symmetry_axis(const Mesh& mesh);

}  // namespace depthtrack
