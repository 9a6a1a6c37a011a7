#include "atlas/triangle_planes.hpp"

#include <Eigen/Geometry>

namespace depthtrack::render {

std::vector<float> triangle_planes(const Mesh& mesh) {
  std::vector<float> planes;
  planes.reserve(mesh.triangles.size() * 4);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<size_t>(t[0])].cast<double>();
    const Eigen::Vector3d n = (mesh.vertices[static_cast<size_t>(t[1])].cast<double>() - a)
                                  .cross(mesh.vertices[static_cast<size_t>(t[2])].cast<double>() - a)
                                  .normalized();
    planes.insert(planes.end(), {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()),
                                 static_cast<float>(n.dot(a))});
  }
  return planes;
}

}  // namespace depthtrack::render
