// Mesh::load: formats, triangulation, node transforms, unit scale, real meshes, and bad files.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <fstream>
#include <string>

#include "support.hpp"

using Catch::Matchers::Contains;
using depthtrack::InputError;
using depthtrack::Mesh;
namespace fs = std::filesystem;

namespace {

fs::path write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

struct Bounds {
  Eigen::Vector3f min, max;
  Eigen::Vector3f size() const { return max - min; }
};

Bounds bounds(const Mesh& mesh) {
  Bounds b{mesh.vertices.at(0), mesh.vertices.at(0)};
  for (const auto& v : mesh.vertices) {
    b.min = b.min.cwiseMin(v);
    b.max = b.max.cwiseMax(v);
  }
  return b;
}

void require_near(const Eigen::Vector3f& actual, const Eigen::Vector3f& expected, float tolerance) {
  INFO("actual " << actual.transpose() << ", expected " << expected.transpose());
  REQUIRE((actual - expected).cwiseAbs().maxCoeff() <= tolerance);
}

// A unit cube from (0,0,0) to (1,1,1) with six quad faces.
const char* kCubeObj = R"(# unit cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

// The tetrahedron (0,0,0), (2,0,0), (0,3,0), (0,0,4).
const char* kTetraPly = R"(ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 0 0
2 0 0
0 3 0
0 0 4
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
)";

const char* kTetraStl = R"(solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 3 0
  vertex 2 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 2 0 0
  vertex 0 0 4
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 4
  vertex 0 3 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 2 0 0
  vertex 0 3 0
  vertex 0 0 4
 endloop
endfacet
endsolid tetra
)";

}  // namespace

TEST_CASE("Mesh::load reads an OBJ cube, triangulating its quads", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_obj") / "cube.obj", kCubeObj);
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 12);
  REQUIRE(mesh.vertices.size() == 8);
  REQUIRE(mesh.dropped_degenerate == 0);
  require_near(bounds(mesh).min, {0, 0, 0}, 0);
  require_near(bounds(mesh).max, {1, 1, 1}, 0);
  require_near(mesh.centre(), {0.5f, 0.5f, 0.5f}, 1e-6f);
}

TEST_CASE("Mesh::load multiplies coordinates by unit_scale", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_scale") / "cube.obj", kCubeObj);
  const Mesh mesh = Mesh::load(path, 0.001);  // millimetres -> metres
  require_near(bounds(mesh).max, {0.001f, 0.001f, 0.001f}, 1e-9f);
  REQUIRE_THROWS_AS(Mesh::load(path, 0.0), InputError);
  REQUIRE_THROWS_AS(Mesh::load(path, -1.0), InputError);
  REQUIRE_THROWS_AS(Mesh::load(path, std::nan("")), InputError);
}

TEST_CASE("Mesh::load splits one OBJ quad into two triangles", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_quad") / "quad.obj",
                               "v 0 0 0\nv 1 0 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4\n");
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 2);
  REQUIRE(mesh.vertices.size() == 4);
}

TEST_CASE("Mesh::load drops OBJ points and lines, keeping the triangles", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_lines") / "mixed.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\nv 8 8 8\nf 1 2 3\nl 4 5\np 4\n");
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 1);
  // The vertices used only by the line and the point are gone too (they would move centre()).
  REQUIRE(mesh.vertices.size() == 3);
  require_near(bounds(mesh).max, {1, 1, 0}, 0);
}

TEST_CASE("Mesh::load reads an ASCII PLY tetrahedron", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_ply") / "tetra.ply", kTetraPly);
  const Mesh mesh = Mesh::load(path, 0.5);
  REQUIRE(mesh.triangles.size() == 4);
  REQUIRE(mesh.vertices.size() == 4);
  require_near(bounds(mesh).min, {0, 0, 0}, 0);
  require_near(bounds(mesh).max, {1.0f, 1.5f, 2.0f}, 1e-6f);
}

TEST_CASE("Mesh::load reads an ASCII STL tetrahedron, joining its repeated vertices", "[io]") {
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_stl") / "tetra.stl", kTetraStl);
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 4);
  REQUIRE(mesh.vertices.size() == 4);
  require_near(bounds(mesh).max, {2, 3, 4}, 1e-6f);
}

TEST_CASE("Mesh::load applies glTF node transforms", "[io]") {
  // One triangle (0,0,0), (1,0,0), (0,1,0) in a child node translated by (1,0,0) under a parent
  // scaled by 2: in the scene's frame it is (2,0,0), (4,0,0), (2,2,0).
  const char* gltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"children": [1], "scale": [2, 2, 2]}, {"mesh": 0, "translation": [1, 0, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 44,
               "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_gltf") / "tri.gltf", gltf);
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 1);
  require_near(bounds(mesh).min, {2, 0, 0}, 1e-6f);
  require_near(bounds(mesh).max, {4, 2, 0}, 1e-6f);
}

TEST_CASE("Mesh::load reads the dbot handset (the thesis' object)", "[io]") {
  const auto path = depthtrack::test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  REQUIRE(mesh.triangles.size() + mesh.dropped_degenerate == 842);
  REQUIRE(mesh.dropped_degenerate == 0);
  require_near(bounds(mesh).size(), {0.0668f, 0.2149f, 0.0694f}, 0.001f);  // 6.7 x 21.5 x 6.9 cm
}

TEST_CASE("Mesh::load reads the Stanford dragon ASCII PLY", "[io]") {
  const auto path = depthtrack::test::shared_data("meshes/stanford/dragon-11102.ply");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  REQUIRE(mesh.triangles.size() + mesh.dropped_degenerate == 11102);
  REQUIRE(bounds(mesh).size().maxCoeff() == Approx(0.20).margin(0.01));  // 20 cm
}

// ---- Bad mesh files ----

TEST_CASE("Mesh::load of a missing file says it does not exist", "[io]") {
  const auto path = depthtrack::test::temp_dir("io_mesh_missing") / "ghost.obj";
  REQUIRE_THROWS_AS(Mesh::load(path), InputError);
  REQUIRE_THROWS_WITH(Mesh::load(path), Contains("ghost.obj") && Contains("does not exist"));
}

TEST_CASE("Mesh::load of an OBJ without faces says it is empty", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_mesh_empty");
  const auto path = write_text(dir / "vertices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  REQUIRE_THROWS_AS(Mesh::load(path), InputError);
  REQUIRE_THROWS_WITH(Mesh::load(path), Contains("vertices.obj") && Contains("is empty"));
  // Points and lines have no area either.
  const auto lines = write_text(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\n");
  REQUIRE_THROWS_WITH(Mesh::load(lines), Contains("lines.obj") && Contains("is empty"));
}

TEST_CASE("Mesh::load of a mesh whose triangles are all degenerate refuses it", "[io]") {
  const auto path =
      write_text(depthtrack::test::temp_dir("io_mesh_degenerate") / "line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  REQUIRE_THROWS_AS(Mesh::load(path), InputError);
  REQUIRE_THROWS_WITH(Mesh::load(path), Contains("line.obj") && Contains("degenerate"));
}

TEST_CASE("Mesh::load drops degenerate triangles and counts them", "[io]") {
  // The cube plus two zero-area triangles: a collinear one and one with a repeated vertex.
  const std::string text = std::string(kCubeObj) + "v 0.5 0 0\nf 1 9 2\nf 1 1 3\n";
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_some_degenerate") / "cube.obj", text);
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 12);
  REQUIRE(mesh.dropped_degenerate == 2);
}

TEST_CASE("Mesh::load of a file of garbage bytes is an InputError naming the file", "[io]") {
  const auto dir = depthtrack::test::temp_dir("io_mesh_garbage");
  std::string garbage;
  uint32_t state = 7;
  for (int i = 0; i < 2000; ++i) {
    state = state * 1664525u + 1013904223u;
    garbage.push_back(static_cast<char>(state >> 24));
  }
  for (const char* name : {"garbage.ply", "garbage.obj", "garbage.stl", "garbage.bin"}) {
    INFO(name);
    const auto path = write_text(dir / name, garbage);
    REQUIRE_THROWS_AS(Mesh::load(path), InputError);
    REQUIRE_THROWS_WITH(Mesh::load(path), Contains(name));
  }
}

TEST_CASE("Mesh::load reads an OBJ whose faces refer to texture coordinates it lacks", "[io]") {
  // The shape of the YCB exports: "f v/vt/vn" with the vt lines stripped; positions are intact.
  const auto path = write_text(depthtrack::test::temp_dir("io_mesh_stripped_vt") / "tri.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n");
  const Mesh mesh = Mesh::load(path);
  REQUIRE(mesh.triangles.size() == 1);
  CHECK(mesh.vertices.size() == 3);
  // A face referring to a missing position is still an error.
  const auto bad =
      write_text(depthtrack::test::temp_dir("io_mesh_bad_position") / "tri.obj", "v 0 0 0\nv 1 0 0\nf 1/1 2/2 9/3\n");
  CHECK_THROWS_AS(Mesh::load(bad), InputError);
}

TEST_CASE("Mesh::load reads the YCB gelatin box", "[io]") {
  const auto path = depthtrack::test::shared_data("meshes/ycb/009_gelatin_box.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  // YCB-Video's own model (textured_simple.obj): 15,728 faces.
  CHECK(mesh.triangles.size() + mesh.dropped_degenerate == 15728);
  Eigen::Vector3f lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // A flat box a few centimetres thick and about ten across.
  const Eigen::Vector3f size = hi - lo;
  CHECK(size.minCoeff() > 0.02f);
  CHECK(size.minCoeff() < 0.04f);
  CHECK(size.maxCoeff() < 0.12f);
}
