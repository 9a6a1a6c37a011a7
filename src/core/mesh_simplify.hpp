#pragma once
// The mesh the tracker draws: a scanned object's 16k triangles are far finer than the pixels of an
// 80x60 working image, and every particle draws every triangle each frame, so the tracker may draw a
// simplified copy whose surface stays within a given distance of the original (TrackerConfig::
// simplify_error), by meshoptimizer's quadric edge collapse.
#include <depthtrack/mesh.hpp>

namespace depthtrack {

struct MeshSimplification {
  Mesh mesh;                  // the vertices it still uses (in their order) and its triangles
  double error = 0;           // meshoptimizer's estimate of the largest distance moved (metres)
  size_t triangles_before = 0;
};

// `mesh` (validated: indices in range) simplified by collapsing edges onto their ends while
// meshoptimizer's estimate of the distance from the original surface stays within max_error metres
// (a quadric estimate: the kept vertices lie on the original surface, and the original vertices were
// measured up to 1.6-2 times max_error from the faces between them, tests/core/test_mesh_simplify.cpp);
// max_error 0 returns the mesh as given.
// Throws InputError for a negative or non-finite max_error.
// target_triangles > 0 stops the simplification there, if the error allows it that far.
MeshSimplification simplify_within(const Mesh& mesh, double max_error, size_t target_triangles = 0);

// The error a tracker draws `mesh` simplified within: simplify_error (TrackerConfig's, metres), but at
// most kMaxRadiusShare of the mesh's radius, so that a small part keeps its shape (the 0.5 mm default
// binds from 2.5 cm of radius up: every mesh measured so far).
inline constexpr double kMaxRadiusShare = 0.02;
double drawing_error(const Mesh& mesh, double simplify_error);
// What a tracker draws of `mesh` (validated) for TrackerConfig::simplify_error: simplify_within at
// drawing_error. The one rule for Tracker and track's note on it.
MeshSimplification simplify_for_drawing(const Mesh& mesh, double simplify_error);
// What a tracker under a frame budget (TrackerConfig::budget_ms) draws: simplify_for_drawing's mesh, but
// one of more than kBudgetTriangles is simplified towards that many within kMaxRadiusShare of its radius
// (unless simplify_error is 0: as given). At 80x60 a pixel spans millimetres; a mesh of fewer triangles
// is left as it is, since its triangles are its shape (the synthetic handset's 842 drawn at 2 % of its
// radius, 268, doubled its ADD-S).
inline constexpr size_t kBudgetTriangles = 1000;
MeshSimplification simplify_for_budget(const Mesh& mesh, double simplify_error);

}  // namespace depthtrack
