#pragma once
// Whether a mesh bounds a solid with its triangles wound outward. Seen from outside such a mesh, the
// nearest surface along every ray faces the camera (a ray enters the solid before it leaves it), so a
// rasterizer may skip the triangles facing away (back-face culling) and keep every depth: half the
// triangles of a closed scan are never drawn.
#include <depthtrack/mesh.hpp>

namespace depthtrack {

// True when every directed edge a->b of the triangles occurs as often as b->a (closed and consistently
// wound, non-manifold edges allowed) and each connected part encloses a positive signed volume (wound
// outward, the normals (b - a) x (c - a) pointing out). False for an open surface (a scan with holes, a
// single sheet), one wound inconsistently, a part wound inward (also a hollow shell's inner wall: safe,
// only slower), an empty mesh and one with an index out of range.
bool bounds_solid_outward(const Mesh& mesh);

}  // namespace depthtrack
