#pragma once
// Mesh::load with its time limit exposed, for tests and the fuzz target (which use a short one).
#include <chrono>
#include <cstdint>
#include <depthtrack/mesh.hpp>
#include <filesystem>

namespace depthtrack {

// Most triangles a mesh may have: every particle renders every triangle each frame, so a larger
// mesh would take minutes per frame in silence; a clear limit is better.
inline constexpr size_t kMaxMeshTriangles = 1'000'000;

// The wall-clock limit Mesh::load gives the importer for a file of this size.
std::chrono::milliseconds mesh_import_time_limit(uintmax_t file_bytes);

// Mesh::load with the importer (assimp, in a child process) stopped after time_limit.
Mesh load_mesh(const std::filesystem::path& path, double unit_scale, std::chrono::milliseconds time_limit);

// The same checks and import in this process, without the child and its time limit: for the fuzz
// targets only, which want the parser itself (libFuzzer's -timeout and -rss_limit_mb are their guard).
// A file that crashes or hangs assimp takes the caller with it.
Mesh load_mesh_unguarded(const std::filesystem::path& path, double unit_scale);

}  // namespace depthtrack
