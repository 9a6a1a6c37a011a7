#pragma once
// A coarser copy of a mesh for scoring many hypotheses: at a working resolution where a pixel spans
// millimetres, a scanned mesh's 16k triangles cost 16 times the rasterization of 1k and change
// almost no pixel.
#include <depthtrack/mesh.hpp>

namespace depthtrack::search {

// Vertex clustering: vertices snap to the mean of their cell in a grid of `cell` metres; triangles
// that collapse, and repeats, are dropped. Returns the mesh unchanged when it would not shrink.
Mesh simplify_mesh(const Mesh& mesh, double cell);

}  // namespace depthtrack::search
