#include "reference/rasterizer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <depthtrack/error.hpp>

namespace depthtrack::reference {

Rasterizer::Rasterizer(const Mesh& mesh, const Camera& camera, double near, double far)
    : triangles_(mesh.triangles), camera_(camera), near_(near), far_(far) {
  camera.validate();
  if (!(near > 0 && far > near)) throw InputError("rasterizer needs 0 < near < far");
  vertices_.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) vertices_.push_back(v.cast<double>());
  transformed_.resize(vertices_.size());
  screen_.resize(vertices_.size());
}

namespace {
// Edge function of the directed edge a->b at point p (twice the signed area of a, b, p).
inline double edge(double au, double av, double bu, double bv, double pu, double pv) {
  return (bu - au) * (pv - av) - (bv - av) * (pu - au);
}
// Top-left tie rule, stated on the edge's coefficients so it holds for either image orientation:
// a centre exactly on an edge is inside for exactly one of the two triangles sharing it.
inline bool owns_edge(double au, double av, double bu, double bv) {
  const double dv = bv - av, du = bu - au;
  return dv < 0 || (dv == 0 && du > 0);
}
}  // namespace

PixelBox Rasterizer::render(const Pose& pose, std::span<float> depth, std::span<int> triangle_ids) const {
  if (depth.size() != static_cast<size_t>(camera_.pixel_count()) ||
      (!triangle_ids.empty() && triangle_ids.size() != depth.size()))
    throw InputError("rasterizer output has the wrong size");
  std::fill(depth.begin(), depth.end(), 0.0f);
  std::fill(triangle_ids.begin(), triangle_ids.end(), -1);
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  auto to_screen = [this](const Eigen::Vector3d& p) {
    return ScreenVertex{camera_.fx * p.x() / p.z() + camera_.cx, camera_.fy * p.y() / p.z() + camera_.cy, 1.0 / p.z()};
  };
  // Each vertex projected once (a vertex is shared by about six triangles): the divisions were most of
  // the time at 80x60, where the triangles of a YCB mesh cover a pixel or none.
  for (size_t i = 0; i < vertices_.size(); ++i) {
    transformed_[i] = r * vertices_[i] + pose.translation;
    if (transformed_[i].z() >= near_) screen_[i] = to_screen(transformed_[i]);
  }
  PixelBox box{camera_.width, camera_.height, 0, 0};
  for (size_t index = 0; index < triangles_.size(); ++index) {
    const Eigen::Vector3i& t = triangles_[index];
    const int id = static_cast<int>(index);
    const std::array<Eigen::Vector3d, 3> p{transformed_[static_cast<size_t>(t[0])],
                                           transformed_[static_cast<size_t>(t[1])],
                                           transformed_[static_cast<size_t>(t[2])]};
    const int in_front = (p[0].z() >= near_) + (p[1].z() >= near_) + (p[2].z() >= near_);
    if (in_front == 0) continue;
    if (in_front == 3) {
      rasterize_triangle(screen_[static_cast<size_t>(t[0])], screen_[static_cast<size_t>(t[1])],
                         screen_[static_cast<size_t>(t[2])], id, depth, triangle_ids, box);
      continue;
    }
    // Cut the triangle at z = near (Sutherland-Hodgman against one plane): 3 or 4 vertices remain.
    std::array<Eigen::Vector3d, 4> clipped;
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& a = p[static_cast<size_t>(i)];
      const Eigen::Vector3d& b = p[static_cast<size_t>((i + 1) % 3)];
      const bool a_in = a.z() >= near_, b_in = b.z() >= near_;
      if (a_in) clipped[static_cast<size_t>(n++)] = a;
      if (a_in != b_in) clipped[static_cast<size_t>(n++)] = a + (b - a) * ((near_ - a.z()) / (b.z() - a.z()));
    }
    for (int i = 1; i + 1 < n; ++i)
      rasterize_triangle(to_screen(clipped[0]), to_screen(clipped[static_cast<size_t>(i)]),
                         to_screen(clipped[static_cast<size_t>(i + 1)]), id, depth, triangle_ids, box);
  }
  if (box.empty()) return PixelBox{};
  return box;
}

void Rasterizer::rasterize_triangle(const ScreenVertex& a, const ScreenVertex& b_in, const ScreenVertex& c_in,
                                    int triangle, std::span<float> depth, std::span<int> triangle_ids,
                                    PixelBox& box) const {
  ScreenVertex b = b_in, c = c_in;
  double area = edge(a.u, a.v, b.u, b.v, c.u, c.v);
  if (area == 0 || !std::isfinite(area)) return;
  if (area < 0) {  // no culling: give every triangle the same orientation
    std::swap(b, c);
    area = -area;
  }
  // Clamped to [-1, size] before the conversion to int, which is undefined beyond int's range: a box
  // off the image comes out empty (u_min > u_max) whatever the vertices' magnitude.
  auto first = [](double lowest, int size) {
    return static_cast<int>(std::clamp(std::ceil(lowest), 0.0, static_cast<double>(size)));
  };
  auto last = [](double highest, int size) {
    return static_cast<int>(std::clamp(std::floor(highest), -1.0, static_cast<double>(size - 1)));
  };
  const int u_min = first(std::min({a.u, b.u, c.u}), camera_.width);
  const int u_max = last(std::max({a.u, b.u, c.u}), camera_.width);
  const int v_min = first(std::min({a.v, b.v, c.v}), camera_.height);
  const int v_max = last(std::max({a.v, b.v, c.v}), camera_.height);
  if (u_min > u_max || v_min > v_max) return;
  const bool own_bc = owns_edge(b.u, b.v, c.u, c.v), own_ca = owns_edge(c.u, c.v, a.u, a.v),
             own_ab = owns_edge(a.u, a.v, b.u, b.v);
  for (int v = v_min; v <= v_max; ++v) {
    for (int u = u_min; u <= u_max; ++u) {
      const double w_a = edge(b.u, b.v, c.u, c.v, u, v);
      const double w_b = edge(c.u, c.v, a.u, a.v, u, v);
      const double w_c = edge(a.u, a.v, b.u, b.v, u, v);
      if (w_a < 0 || w_b < 0 || w_c < 0) continue;
      if ((w_a == 0 && !own_bc) || (w_b == 0 && !own_ca) || (w_c == 0 && !own_ab)) continue;
      const double inv_z = (w_a * a.inv_z + w_b * b.inv_z + w_c * c.inv_z) / area;
      const double z = 1.0 / inv_z;
      if (z < near_ || z > far_) continue;
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(camera_.width) + static_cast<size_t>(u);
      float& out = depth[k];
      if (out == 0.0f || z < out) {
        out = static_cast<float>(z);
        if (!triangle_ids.empty()) triangle_ids[k] = triangle;
        box.u0 = std::min(box.u0, u);
        box.v0 = std::min(box.v0, v);
        box.u1 = std::max(box.u1, u + 1);
        box.v1 = std::max(box.v1, v + 1);
      }
    }
  }
}

}  // namespace depthtrack::reference
