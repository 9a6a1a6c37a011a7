#pragma once
/// @file
/// A triangle mesh in the object frame (metres after unit_scale).
#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace depthtrack {

/// A triangle mesh in the object frame (metres after unit_scale).
struct Mesh {
  std::vector<Eigen::Vector3f> vertices;   ///< object frame, metres
  std::vector<Eigen::Vector3i> triangles;  ///< indices into vertices
  /// Triangles with (near) zero area that load() dropped: they can never cover a pixel.
  size_t dropped_degenerate = 0;

  /// Any format assimp reads (OBJ, PLY, STL, glTF, ...), all meshes of the scene merged and
  /// triangulated, node transforms applied, each coordinate multiplied by unit_scale.
  /// Throws InputError for a missing or unreadable file, no triangles, non-finite coordinates,
  /// or a mesh whose triangles are all degenerate.
  static Mesh load(const std::filesystem::path& path, double unit_scale = 1.0);
  /// Checks indices, finiteness and that some triangle has an area; drops degenerate triangles.
  /// `what` names the mesh in the InputError thrown for a bad index, a coordinate that is not finite, or no
  /// triangle with an area.
  void validate_and_clean(const std::string& what);

  /// Mean of the vertices: the point motion noise rotates about (MODEL.md).
  Eigen::Vector3f centre() const;
  /// Largest distance of a vertex from centre().
  float radius() const;
};

/// A procedural, asymmetric object (two joined boxes, about 16 x 9 x 6 cm) for the demo and tests:
/// the real meshes (YCB) are licensed separately and not shipped with the library.
Mesh builtin_demo_mesh();
/// An axis-aligned box centred at the origin with the given edge lengths (12 triangles).
Mesh make_box(const Eigen::Vector3f& size, const Eigen::Vector3f& centre = Eigen::Vector3f::Zero());
/// Appends other's triangles to mesh.
void append_mesh(Mesh& mesh, const Mesh& other);

}  // namespace depthtrack
