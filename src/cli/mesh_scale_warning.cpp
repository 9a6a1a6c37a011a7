#include "cli/mesh_scale_warning.hpp"

#include <cstdio>

namespace depthtrack::cli {

double mesh_span(const Mesh& mesh) {
  if (mesh.vertices.empty()) return 0;
  Eigen::Vector3f lo = mesh.vertices.front(), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return static_cast<double>((hi - lo).maxCoeff());
}

bool warn_if_mesh_scale_unusual(const Mesh& mesh, const std::string& path, double unit_scale) {
  const double span = mesh_span(mesh);
  if (span >= 0.001 && span <= 5.0) return false;
  // Millimetre meshes read as metres are the usual case (BOP, CAD exports).
  std::fprintf(stderr,
               "depthtrack: warning: mesh '%s' spans %.4g m with --unit-scale %g, outside 1 mm to 5 m: check "
               "--unit-scale (1 for a mesh in metres, 0.001 for one in millimetres)\n",
               path.c_str(), span, unit_scale);
  return true;
}

}  // namespace depthtrack::cli
