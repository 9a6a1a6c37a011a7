#pragma once
// Sequential z-buffer rasterizer producing metric z-depth. Its conventions are the ones the GL atlas
// renderer follows, so the two can be compared pixel by pixel:
//  - pixel (u, v) is covered when its centre, image coordinate (u, v), lies inside the projected
//    triangle; a centre exactly on an edge belongs to the triangle for which the edge is top or left;
//  - its depth is the camera-frame z of the triangle's plane along the ray through that centre
//    (what perspective-correct interpolation of z gives);
//  - geometry nearer than `near` is clipped away (triangles are cut at z = near), fragments farther
//    than `far` are discarded; uncovered pixels hold 0;
//  - where the mesh bounds a solid wound outward (bounds_solid_outward), the triangles facing away from
//    the camera are skipped: never the nearest seen from outside, so the depths are the same.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <memory>
#include <span>
#include <vector>

#include "core/thread_pool.hpp"

namespace depthtrack::reference {

// Pixel rectangle [u0, u1) x [v0, v1) that a rendering covers; empty when u0 >= u1.
struct PixelBox {
  int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
  bool empty() const { return u0 >= u1 || v0 >= v1; }
};

class Rasterizer {
 public:
  Rasterizer(const Mesh& mesh, const Camera& camera, double near, double far);

  // Writes camera.width * camera.height depths (row-major) into depth; returns the covered box.
  // triangle_ids, when not empty (same size as depth), receives the index of the mesh triangle whose
  // depth each pixel kept, -1 where none: what a pose refinement needs for surface normals.
  PixelBox render(const Pose& camera_from_object, std::span<float> depth, std::span<int> triangle_ids = {}) const;

  // Renders without triangle ids then split over pool's threads (each draws a share of the triangles into
  // a depth image of its own; the nearest depth is kept): the same depths, bit for bit, since the nearest
  // of the float depths does not depend on the order the triangles come in. A null pool, or one thread,
  // draws on the caller's thread alone. The pool is shared by no concurrent render.
  void split_over(std::shared_ptr<ThreadPool> pool);

  const Camera& camera() const { return camera_; }
  // Whether the triangles facing away are skipped (the mesh bounds a solid wound outward).
  bool culls_back_faces() const { return cull_back_faces_; }

 private:
  struct ScreenVertex {
    double u, v, inv_z;
  };
  // The pixel columns and rows a vertex bounds: first_pixel and last_pixel of its u and v.
  struct VertexPixels {
    int u_first, u_last, v_first, v_last;
  };
  void project_vertices(size_t begin, size_t end, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation) const;
  void draw_triangles(size_t begin, size_t end, std::span<float> depth, std::span<int> triangle_ids,
                      PixelBox& box) const;
  PixelBox render_split(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
                        std::span<float> depth) const;
  ScreenVertex to_screen(const Eigen::Vector3d& p) const;
  void rasterize_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int triangle,
                          std::span<float> depth, std::span<int> triangle_ids, PixelBox& box) const;
  // rasterize_triangle's pixels, once the triangle's area and pixel box [u_min, u_max] x [v_min, v_max]
  // say it may cover some.
  void fill_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, double area, int u_min,
                     int u_max, int v_min, int v_max, int triangle, std::span<float> depth, std::span<int> triangle_ids,
                     PixelBox& box) const;

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::Vector3i> triangles_;
  Camera camera_;
  double near_, far_;
  bool cull_back_faces_;                              // bounds_solid_outward(mesh)
  mutable std::vector<Eigen::Vector3d> transformed_;  // scratch: vertices in the camera frame
  mutable std::vector<ScreenVertex> screen_;          // scratch: projected (read only in front of near)
  mutable std::vector<VertexPixels> bounds_;          // scratch: their pixel bounds
  mutable std::vector<unsigned char> in_front_;       // scratch: 1 where z >= near
  std::shared_ptr<ThreadPool> pool_;                  // split_over's, or null
  mutable std::vector<std::vector<float>> parts_;     // the pool's other threads' depths, kept all 0 between renders
  mutable std::vector<PixelBox> part_boxes_;          // each thread's share's box (render_split)
};

}  // namespace depthtrack::reference
