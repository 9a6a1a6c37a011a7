#pragma once
// Triangles grouped by the way they face, so that a drawing can skip, with one test, every triangle of a
// group that faces away from the camera. Each particle's drawing lists a fine mesh's triangles one by
// one (cl/render_weigh.cl): loading a triangle's corners and testing its facing cost as much for the half
// that faces away and draws nothing as for the rest. A bin holds the triangles whose outward normals lie
// within a cone (a cell of a cube map of directions) and bounds their corners by a sphere; a camera that
// sees every one of them from behind, with a margin, lets the whole bin go untested.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <depthtrack/mesh.hpp>
#include <vector>

namespace depthtrack {

struct FacingBin {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // of the sphere around its triangles' corners (object frame)
  float radius = 0;
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();  // the normals' cone: each normal n has n . axis >= cos_half_angle
  float cos_half_angle = -1;                         // -1: never skipped (degenerate normals)
};

struct FacingOrder {
  // The triangles in bin order: the i-th is the mesh's triangle order[i]; bin_of[i] is its bin.
  std::vector<uint32_t> order;
  std::vector<uint16_t> bin_of;
  std::vector<FacingBin> bins;
};

// A cube map of cells_per_face x cells_per_face cells on each of its six faces (at most 6 x 5 x 5 = 150
// bins, and one for triangles without a normal); empty cells make no bin. Normals are (b - a) x (c - a),
// outward for a mesh that bounds_solid_outward. Seen from 0.8 m in 300 directions, 5 cells a side skip
// 35 % of the YCB mug's triangles, 38 % of the handset's (3: 28 and 31 %; a closed mesh faces away with
// half of them at most: the cones' width and the spheres' size take the rest).
inline constexpr int kFacingCellsPerFace = 5;
inline constexpr size_t kMostFacingBins = 6 * kFacingCellsPerFace * kFacingCellsPerFace + 1;
FacingOrder facing_order(const Mesh& mesh, int cells_per_face = kFacingCellsPerFace);

// Whether every triangle of `bin` faces away from a camera at `camera` (object frame) by a margin: the
// camera lies behind each one's plane by more than kFacingMargin of its distance to the bin's centre,
// so that a float test of the projected triangle's winding cannot come out the other way. The same
// float arithmetic as cl/rasterize.cl's dt_bin_faces_away.
inline constexpr float kFacingMargin = 1e-3f;
bool bin_faces_away(const FacingBin& bin, const Eigen::Vector3f& camera);

// The bins as the kernels read them: 8 floats each, centre x y z, radius, axis x y z, cos_half_angle.
std::vector<float> packed_bins(const std::vector<FacingBin>& bins);

}  // namespace depthtrack
