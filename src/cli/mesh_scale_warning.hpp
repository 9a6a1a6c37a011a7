#pragma once
// A mesh whose size is implausible for a tracked object was most likely loaded in the wrong unit.
#include <depthtrack/mesh.hpp>
#include <string>

namespace depthtrack::cli {

// The mesh's largest bounding-box side in metres.
double mesh_span(const Mesh& mesh);
// Prints a warning naming --unit-scale to stderr when the span is under 1 mm or over 5 m; returns
// whether it warned.
bool warn_if_mesh_scale_unusual(const Mesh& mesh, const std::string& path, double unit_scale);

}  // namespace depthtrack::cli
