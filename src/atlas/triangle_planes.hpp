#pragma once
// Each triangle's object-frame plane, for renderers that take a pixel's depth from the plane along
// its ray rather than from interpolation (atlas.frag, cl/rasterize.cl).
#include <depthtrack/mesh.hpp>
#include <vector>

namespace depthtrack::render {

// Per triangle the unit normal n and offset d with n . x = d (4 floats), computed in double like
// the reference's depths; a degenerate triangle gets n = 0 and covers no pixel.
std::vector<float> triangle_planes(const Mesh& mesh);

}  // namespace depthtrack::render
