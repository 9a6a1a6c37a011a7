#include "reference/rasterizer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <depthtrack/error.hpp>

#include "core/mesh_topology.hpp"

namespace depthtrack::reference {

Rasterizer::Rasterizer(const Mesh& mesh, const Camera& camera, double near, double far)
    : triangles_(mesh.triangles),
      camera_(camera),
      near_(near),
      far_(far),
      cull_back_faces_(bounds_solid_outward(mesh)) {
  camera.validate();
  if (!(near > 0 && far > near)) throw InputError("rasterizer needs 0 < near < far");
  vertices_.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) vertices_.push_back(v.cast<double>());
  transformed_.resize(vertices_.size());
  screen_.resize(vertices_.size());
  bounds_.resize(vertices_.size());
  in_front_.resize(vertices_.size());
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

// Where a triangle can cover pixel centres: its doubled signed area (oriented as the vertices come) and
// the box of pixels around it.
struct Cover {
  double area;
  int u_min, u_max, v_min, v_max;
};

// ceil(lowest) clamped to [0, size] and floor(highest) to [-1, size - 1], compared before the conversion
// to int (undefined beyond int's range): a box off the image comes out empty whatever the vertices'
// magnitude. The vertices are finite (a non-finite one makes the area non-finite), and within the clamps
// the conversion's truncation is the floor, so no ceil or floor is needed.
inline int first_pixel(double lowest, int size) {
  if (!(lowest > 0)) return 0;
  if (lowest >= size) return size;
  const int t = static_cast<int>(lowest);
  return t + (static_cast<double>(t) < lowest ? 1 : 0);
}
inline int last_pixel(double highest, int size) {
  if (!(highest >= 0)) return -1;
  if (highest >= size - 1) return size - 1;
  return static_cast<int>(highest);
}

// first_pixel and last_pixel without a branch: the clamps in double (a NaN taken as the lowest), then
// the truncation.
inline int first_pixel_of(double lowest, int size) {
  double c = lowest > 0 ? lowest : 0.0;
  const double top = size;
  c = c < top ? c : top;
  const int t = static_cast<int>(c);
  return t + static_cast<int>(static_cast<double>(t) < c);
}
inline int last_pixel_of(double highest, int size) {
  double c = highest >= 0 ? highest : -1.0;
  const double top = size - 1;
  c = c < top ? c : top;
  return static_cast<int>(c);
}

// False for a triangle that covers no pixel centre for sure: of zero or non-finite area, facing away
// (cull), or with no pixel centre in its box. At 80x60 that is most triangles of a fine mesh, so this
// runs inline, before anything else is computed.
template <typename Vertex>
inline bool may_cover(const Vertex& a, const Vertex& b, const Vertex& c, bool cull, int width, int height,
                      Cover& cover) {
  cover.area = edge(a.u, a.v, b.u, b.v, c.u, c.v);
  // Facing the camera, a triangle wound outward runs clockwise in the image (v down): area < 0.
  if (cover.area == 0 || !std::isfinite(cover.area) || (cull && cover.area > 0)) return false;
  cover.u_min = first_pixel(std::min(std::min(a.u, b.u), c.u), width);
  cover.u_max = last_pixel(std::max(std::max(a.u, b.u), c.u), width);
  if (cover.u_min > cover.u_max) return false;
  cover.v_min = first_pixel(std::min(std::min(a.v, b.v), c.v), height);
  cover.v_max = last_pixel(std::max(std::max(a.v, b.v), c.v), height);
  return cover.v_min <= cover.v_max;
}
}  // namespace

void Rasterizer::split_over(std::shared_ptr<ThreadPool> pool) {
  pool_ = pool && pool->size() > 1 ? std::move(pool) : nullptr;
  parts_.assign(pool_ ? static_cast<size_t>(pool_->size() - 1) : 0,
                std::vector<float>(static_cast<size_t>(camera_.pixel_count()), 0.0f));
  part_boxes_.resize(pool_ ? static_cast<size_t>(pool_->size()) : 0);
}

Rasterizer::ScreenVertex Rasterizer::to_screen(const Eigen::Vector3d& p) const {
  return ScreenVertex{camera_.fx * p.x() / p.z() + camera_.cx, camera_.fy * p.y() / p.z() + camera_.cy, 1.0 / p.z()};
}

// Each vertex projected once (a vertex is shared by about six triangles): the divisions were most of
// the time at 80x60, where the triangles of a YCB mesh cover a pixel or none. With it, the pixel columns
// and rows it bounds: first_pixel and last_pixel grow with their argument, so a triangle's box is the
// least first and the greatest last of its vertices' (may_cover's box, without four conversions a
// triangle). Without a branch: a vertex behind near is projected too (what it gives is never read).
void Rasterizer::project_vertices(size_t begin, size_t end, const Eigen::Matrix3d& rotation,
                                  const Eigen::Vector3d& translation) const {
  for (size_t i = begin; i < end; ++i) {
    const Eigen::Vector3d p = rotation * vertices_[i] + translation;
    transformed_[i] = p;
    in_front_[i] = static_cast<unsigned char>(p.z() >= near_);
    const ScreenVertex s = to_screen(p);
    screen_[i] = s;
    bounds_[i] = VertexPixels{first_pixel_of(s.u, camera_.width), last_pixel_of(s.u, camera_.width),
                              first_pixel_of(s.v, camera_.height), last_pixel_of(s.v, camera_.height)};
  }
}

void Rasterizer::draw_triangles(size_t begin, size_t end, std::span<float> depth, std::span<int> triangle_ids,
                                PixelBox& box) const {
  for (size_t index = begin; index < end; ++index) {
    const Eigen::Vector3i& t = triangles_[index];
    const int id = static_cast<int>(index);
    const size_t i0 = static_cast<size_t>(t[0]), i1 = static_cast<size_t>(t[1]), i2 = static_cast<size_t>(t[2]);
    const int in_front = in_front_[i0] + in_front_[i1] + in_front_[i2];
    if (in_front == 0) continue;
    if (in_front == 3) {
      // may_cover's tests, the box from the vertices' bounds.
      const ScreenVertex &a = screen_[i0], &b = screen_[i1], &c = screen_[i2];
      const double area = edge(a.u, a.v, b.u, b.v, c.u, c.v);
      if (area == 0 || !std::isfinite(area) || (cull_back_faces_ && area > 0)) continue;
      const VertexPixels &pa = bounds_[i0], &pb = bounds_[i1], &pc = bounds_[i2];
      const int u_min = std::min(std::min(pa.u_first, pb.u_first), pc.u_first);
      const int u_max = std::max(std::max(pa.u_last, pb.u_last), pc.u_last);
      if (u_min > u_max) continue;
      const int v_min = std::min(std::min(pa.v_first, pb.v_first), pc.v_first);
      const int v_max = std::max(std::max(pa.v_last, pb.v_last), pc.v_last);
      if (v_min > v_max) continue;
      fill_triangle(a, b, c, area, u_min, u_max, v_min, v_max, id, depth, triangle_ids, box);
      continue;
    }
    const std::array<Eigen::Vector3d, 3> p{transformed_[i0], transformed_[i1], transformed_[i2]};
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
}

PixelBox Rasterizer::render(const Pose& pose, std::span<float> depth, std::span<int> triangle_ids) const {
  if (depth.size() != static_cast<size_t>(camera_.pixel_count()) ||
      (!triangle_ids.empty() && triangle_ids.size() != depth.size()))
    throw InputError("rasterizer output has the wrong size");
  std::fill(depth.begin(), depth.end(), 0.0f);
  std::fill(triangle_ids.begin(), triangle_ids.end(), -1);
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  if (pool_ && triangle_ids.empty()) return render_split(r, pose.translation, depth);
  project_vertices(0, vertices_.size(), r, pose.translation);
  PixelBox box{camera_.width, camera_.height, 0, 0};
  draw_triangles(0, triangles_.size(), depth, triangle_ids, box);
  if (box.empty()) return PixelBox{};
  return box;
}

// Part 0 draws into depth, part p > 0 into parts_[p - 1]; each part's nearest depths then go into depth
// and its image back to 0 (only its box was written).
PixelBox Rasterizer::render_split(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
                                  std::span<float> depth) const {
  const size_t parts = static_cast<size_t>(pool_->size());
  const auto share = [parts](size_t count, size_t part) { return count * part / parts; };
  pool_->run(parts, [&](size_t part, int) {
    project_vertices(share(vertices_.size(), part), share(vertices_.size(), part + 1), rotation, translation);
  });
  std::vector<PixelBox>& boxes = part_boxes_;
  std::fill(boxes.begin(), boxes.end(), PixelBox{camera_.width, camera_.height, 0, 0});
  pool_->run(parts, [&](size_t part, int) {
    const std::span<float> out = part == 0 ? depth : std::span<float>(parts_[part - 1]);
    draw_triangles(share(triangles_.size(), part), share(triangles_.size(), part + 1), out, {}, boxes[part]);
  });
  PixelBox box = boxes[0];
  const size_t width = static_cast<size_t>(camera_.width);
  for (size_t part = 1; part < parts; ++part) {
    const PixelBox& b = boxes[part];
    std::vector<float>& drawn = parts_[part - 1];
    for (int v = b.v0; v < b.v1; ++v)
      for (int u = b.u0; u < b.u1; ++u) {
        const size_t k = static_cast<size_t>(v) * width + static_cast<size_t>(u);
        const float z = drawn[k];
        if (z > 0.0f && (depth[k] == 0.0f || z < depth[k])) depth[k] = z;
        drawn[k] = 0.0f;
      }
    box.u0 = std::min(box.u0, b.u0);
    box.v0 = std::min(box.v0, b.v0);
    box.u1 = std::max(box.u1, b.u1);
    box.v1 = std::max(box.v1, b.v1);
  }
  if (box.empty()) return PixelBox{};
  return box;
}

void Rasterizer::rasterize_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int triangle,
                                    std::span<float> depth, std::span<int> triangle_ids, PixelBox& box) const {
  Cover cover;
  if (may_cover(a, b, c, cull_back_faces_, camera_.width, camera_.height, cover))
    fill_triangle(a, b, c, cover.area, cover.u_min, cover.u_max, cover.v_min, cover.v_max, triangle, depth,
                  triangle_ids, box);
}

void Rasterizer::fill_triangle(const ScreenVertex& a, const ScreenVertex& b_in, const ScreenVertex& c_in, double area,
                               int u_min, int u_max, int v_min, int v_max, int triangle, std::span<float> depth,
                               std::span<int> triangle_ids, PixelBox& box) const {
  const ScreenVertex* pb = &b_in;
  const ScreenVertex* pc = &c_in;
  if (area < 0) {  // give every triangle drawn the same orientation
    std::swap(pb, pc);
    area = -area;
  }
  const ScreenVertex &b = *pb, &c = *pc;
  for (int v = v_min; v <= v_max; ++v) {
    for (int u = u_min; u <= u_max; ++u) {
      const double w_a = edge(b.u, b.v, c.u, c.v, u, v);
      const double w_b = edge(c.u, c.v, a.u, a.v, u, v);
      const double w_c = edge(a.u, a.v, b.u, b.v, u, v);
      if (w_a < 0 || w_b < 0 || w_c < 0) continue;
      // A centre on an edge (rare): the tie rule.
      if ((w_a == 0 && !owns_edge(b.u, b.v, c.u, c.v)) || (w_b == 0 && !owns_edge(c.u, c.v, a.u, a.v)) ||
          (w_c == 0 && !owns_edge(a.u, a.v, b.u, b.v)))
        continue;
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
