// Mesh import that cannot take the process down: crashes, aborts and endless loops of the importer
// become InputErrors in bounded time, and out-of-range indices are caught by validation.
#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <depthtrack/error.hpp>
#include <fstream>
#include <string>
#include <thread>

#include "io/isolated_call.hpp"
#include "io/mesh_import.hpp"
#include "support.hpp"

using Catch::Matchers::Contains;
using depthtrack::InputError;
namespace fs = std::filesystem;

namespace {

constexpr std::chrono::milliseconds kShortLimit{1500};

fs::path write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The message of the InputError that f throws (fails the test if it throws none).
template <typename F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("no InputError");
  return "";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A binary little-endian PLY triangle whose face names vertex 7 of 3.
std::string ply_with_out_of_range_index() {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  s.push_back(3);
  const int f[3] = {0, 1, 7};
  s.append(reinterpret_cast<const char*>(f), sizeof f);
  return s;
}

}  // namespace

TEST_CASE("call_isolated hands back the child's answer and its InputErrors", "[io][robustness]") {
  CHECK(depthtrack::io::call_isolated([] { return std::string("a\0b", 3); }, kShortLimit, "x") ==
        std::string("a\0b", 3));
  CHECK_THROWS_WITH(
      depthtrack::io::call_isolated([]() -> std::string { throw InputError("bad vertex 3"); }, kShortLimit, "x"),
      "bad vertex 3");
}

TEST_CASE("call_isolated turns a crash, an abort and an endless loop into InputErrors naming the input",
          "[io][robustness]") {
  using depthtrack::io::call_isolated;
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(input_error_of([] {
               call_isolated(
                   []() -> std::string {
                     std::raise(SIGSEGV);
                     return "";
                   },
                   kShortLimit, "mesh 'a'");
             }),
             Contains("mesh 'a'") && Contains("crashed (signal 11"));
  CHECK_THAT(input_error_of([] { call_isolated([]() -> std::string { std::abort(); }, kShortLimit, "mesh 'b'"); }),
             Contains("mesh 'b'") && Contains("signal 6"));
  CHECK_THAT(input_error_of([] {
               call_isolated(
                   []() -> std::string {
                     for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
                   },
                   std::chrono::milliseconds(300), "mesh 'c'");
             }),
             Contains("mesh 'c'") && Contains("no answer within 0.30 s"));
  CHECK_THAT(input_error_of([] { call_isolated([]() -> std::string { std::_Exit(0); }, kShortLimit, "mesh 'd'"); }),
             Contains("mesh 'd'") && Contains("without an answer"));
  CHECK(seconds_since(start) < 5);
}

TEST_CASE("Mesh::load of a binary PLY whose face names a missing vertex is a validation error", "[io][robustness]") {
  const auto path =
      write_bytes(depthtrack::test::temp_dir("mesh_hostile") / "bad_index.ply", ply_with_out_of_range_index());
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(path); }),
             Contains("bad_index.ply") && Contains("out of range"));
}

TEST_CASE("Mesh::load refuses a mesh of more than a million triangles before processing it", "[io][robustness]") {
  // Binary STL: 80-byte header, a count, 50 bytes per triangle (normal, 3 corners, attribute).
  const uint32_t count = static_cast<uint32_t>(depthtrack::kMaxMeshTriangles) + 1;
  std::string stl(80, ' ');
  stl.append(reinterpret_cast<const char*>(&count), 4);
  std::string triangle(50, '\0');
  for (uint32_t i = 0; i < count; ++i) {
    const float corners[12] = {
        0, 0, 1, static_cast<float>(i), 0, 0, static_cast<float>(i) + 1, 0, 0, static_cast<float>(i), 1, 0};
    std::memcpy(triangle.data(), corners, sizeof corners);
    stl += triangle;
  }
  const auto path = write_bytes(depthtrack::test::temp_dir("mesh_huge") / "huge.stl", stl);
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(path); }),
             Contains("huge.stl") && Contains("1000001 triangles") && Contains("simplify"));
  CHECK(seconds_since(start) < 20);
  fs::remove(path);
}

TEST_CASE("Mesh::load of the fuzzer's reproducers in ../shared/robustness gives clear errors in bounded time",
          "[io][robustness]") {
  for (const char* file : {"repro_obj_retry_segv_19B.obj", "repro_assimp_binary_ply_box.ply",
                           "repro_assimp_ply_triangulate_abort.ply", "repro_assimp_ply_hang_166B.ply"}) {
    const auto path = depthtrack::test::shared_data(std::string("../robustness/") + file);
    if (!path) return;
    INFO(file);
    const auto start = std::chrono::steady_clock::now();
    CHECK_THAT(input_error_of([&] { depthtrack::load_mesh(*path, 1.0, kShortLimit); }), Contains(file));
    CHECK(seconds_since(start) < 5);
  }
}

TEST_CASE("an OFF file whose header declares more vertices or faces than its bytes hold is refused at once",
          "[io][robustness]") {
  // assimp's OFF reader reserved and touched gigabytes for these (the fuzzer's out-of-memory and time-outs).
  const auto dir = depthtrack::test::temp_dir("mesh_off_counts");
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto faces = write_bytes(dir / "faces.off", "OFF\n3 999999990 0\n" + body);
  const auto vertices = write_bytes(dir / "vertices.off", "OFF\n# comment\n499999999 1 0\n" + body);
  const auto digits = write_bytes(dir / "digits.off", "OFF\n3 9999999999[9OFF 0\n" + body);  // read as assimp does
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(faces); }),
             Contains("faces.off") && Contains("declares 3 vertices and 999999990 faces") && Contains("bytes"));
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(vertices); }), Contains("declares 499999999 vertices"));
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(digits); }), Contains("9999999999 faces"));
  CHECK(seconds_since(start) < 5);
  // The same body with its true counts loads: one triangle.
  const auto good = write_bytes(dir / "good.off", "OFF\n3 1 0\n" + body);
  const depthtrack::Mesh mesh = depthtrack::Mesh::load(good);
  CHECK(mesh.vertices.size() == 3);
  CHECK(mesh.triangles.size() == 1);
}

TEST_CASE("a PLY header whose end_header does not open a line is refused at once", "[io][robustness]") {
  // assimp's reader looked for the line forever (the fuzzer's 33-byte time-out).
  const auto path =
      write_bytes(depthtrack::test::temp_dir("mesh_ply_end") / "inline.ply", "ply\nformat ascii 1.0\npfend_header\n");
  const auto start = std::chrono::steady_clock::now();
  CHECK_THAT(input_error_of([&] { depthtrack::Mesh::load(path); }),
             Contains("inline.ply") && Contains("no 'end_header' line"));
  CHECK(seconds_since(start) < 5);
}
