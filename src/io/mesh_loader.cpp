// Mesh::load through assimp: every format it reads, merged into one triangle list.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/isolated_call.hpp"
#include "io/mesh_import.hpp"

namespace depthtrack {

namespace {

// Appends one assimp mesh (already in the scene's root frame) to out, keeping only triangles:
// point and line primitives have no area to render.
void append_triangles(const aiMesh& in, double unit_scale, const std::string& what, Mesh& out) {
  const int offset = static_cast<int>(out.vertices.size());
  for (unsigned i = 0; i < in.mNumVertices; ++i) {
    const aiVector3D& v = in.mVertices[i];
    out.vertices.emplace_back(static_cast<float>(v.x * unit_scale), static_cast<float>(v.y * unit_scale),
                              static_cast<float>(v.z * unit_scale));
  }
  for (unsigned i = 0; i < in.mNumFaces; ++i) {
    const aiFace& face = in.mFaces[i];
    if (face.mNumIndices != 3) continue;
    for (int k = 0; k < 3; ++k)
      if (face.mIndices[k] >= in.mNumVertices) throw InputError(what + ": a face refers to a missing vertex");
    out.triangles.emplace_back(offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                               offset + static_cast<int>(face.mIndices[2]));
  }
}

// Merges vertices at the same position and drops those no triangle uses. Formats such as STL
// repeat every corner per face, and JoinIdenticalVertices keeps corners whose normals or texture
// coordinates differ; but centre() is a mean over vertices, so each point must count once.
void weld(Mesh& mesh, const std::string& what) {
  std::map<std::array<float, 3>, int> index_of;  // ordered by value, so -0 and +0 are one point
  std::vector<Eigen::Vector3f> kept;
  for (auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f& v = mesh.vertices[static_cast<size_t>(t[k])];
      if (!v.allFinite()) throw InputError(what + ": vertex " + std::to_string(t[k]) + " has a non-finite coordinate");
      const auto [it, added] = index_of.try_emplace({v.x(), v.y(), v.z()}, static_cast<int>(kept.size()));
      if (added) kept.push_back(v);
      t[k] = it->second;
    }
  mesh.vertices = std::move(kept);
}

bool has_polygons(const aiScene& scene) {
  for (unsigned i = 0; i < scene.mNumMeshes; ++i)
    for (unsigned j = 0; j < scene.mMeshes[i]->mNumFaces; ++j)
      if (scene.mMeshes[i]->mFaces[j].mNumIndices >= 3) return true;
  return false;
}

// Checked before post-processing, which would spend minutes on a huge mesh.
void check_triangle_limit(const aiScene& scene, const std::string& name) {
  uint64_t triangles = 0;  // as Triangulate will make them: n - 2 per polygon of n corners
  for (unsigned i = 0; i < scene.mNumMeshes; ++i)
    for (unsigned j = 0; j < scene.mMeshes[i]->mNumFaces; ++j) {
      const unsigned corners = scene.mMeshes[i]->mFaces[j].mNumIndices;
      if (corners >= 3) triangles += corners - 2;  // points and lines are dropped
    }
  if (triangles > kMaxMeshTriangles)
    throw InputError(name + " has " + std::to_string(triangles) + " triangles, more than the " +
                     std::to_string(kMaxMeshTriangles) +
                     " depthtrack takes (every particle renders every triangle each frame): simplify the mesh");
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool is_obj(const std::filesystem::path& path) {
  return lower_extension(path) == ".obj";
}

// Bytes a PLY value of this type takes in binary; 0 for a type name assimp would not read either.
size_t ply_type_bytes(const std::string& type) {
  static const std::pair<const char*, size_t> sizes[] = {{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
                                                         {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
                                                         {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
                                                         {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : sizes)
    if (type == name) return bytes;
  return 0;
}

// Like the OFF counts below: assimp reserves what "element vertex N" declares, so a short file claiming
// four billion vertices ends in an allocation failure. Each element takes at least its properties'
// bytes (binary: a scalar's size, a list's count; ASCII: a character and a separator per property),
// so counts the data after the header cannot hold are refused before assimp sees the file.
void check_ply_counts(const std::filesystem::path& path, const std::string& name, const std::string& header,
                      size_t header_bytes) {
  std::istringstream lines(header);
  bool ascii = false;
  std::vector<std::pair<std::string, uint64_t>> elements;  // name, count
  long double needed = 0, element_bytes = 0;
  const auto close_element = [&] {
    if (!elements.empty()) needed += static_cast<long double>(elements.back().second) * element_bytes;
    element_bytes = 0;
  };
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword, a, b, c;
    words >> keyword >> a >> b >> c;
    if (keyword == "format") ascii = a == "ascii";
    if (keyword == "element") {
      close_element();
      uint64_t count = 0;
      for (size_t i = 0; i < b.size() && std::isdigit(static_cast<unsigned char>(b[i])); ++i)
        count = std::min<uint64_t>(count * 10 + static_cast<uint64_t>(b[i] - '0'), uint64_t{1} << 60);
      elements.emplace_back(a, count);
    }
    if (keyword == "property" && !elements.empty())
      element_bytes += ascii ? 2 : static_cast<long double>(ply_type_bytes(a == "list" ? b : a));
  }
  close_element();
  std::error_code error;
  const uintmax_t bytes = std::filesystem::file_size(path, error);
  if (error || bytes < header_bytes) return;
  const uintmax_t data = bytes - header_bytes;
  if (needed <= static_cast<long double>(data)) return;
  std::string claims;
  for (const auto& [element, count] : elements)
    claims += (claims.empty() ? "" : ", ") + std::to_string(count) + " " + element;
  throw InputError(name + ": the file's header claims more than it holds: " + claims + " elements need at least " +
                   std::to_string(static_cast<uintmax_t>(std::min<long double>(needed, 1e18L))) + " bytes, " +
                   "but only " + std::to_string(data) + " follow the header (the file is cut short or malformed)");
}

// assimp's PLY reader loops forever on a header it cannot finish: a PLY must say "ply" and end its
// header within its first MiB (real headers take a few hundred bytes). Clearer, and at once.
void check_ply_header(const std::filesystem::path& path, const std::string& name) {
  if (lower_extension(path) != ".ply") return;
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 20, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  if (head.rfind("ply", 0) != 0) throw InputError(name + " is not a PLY file: it does not start with 'ply'");
  // The keyword must open a line of its own ("pfend_header" made assimp loop as well).
  const size_t line = head.find("\nend_header");
  const size_t end = line == std::string::npos ? line : line + 1;
  if (end == std::string::npos || head.find_first_not_of(" \t\r\n", end + 10) < head.find('\n', end))
    throw InputError(name + ": its PLY header has no 'end_header' line within the first MiB");
  const size_t newline = head.find('\n', end);
  check_ply_counts(path, name, head.substr(0, end), newline == std::string::npos ? head.size() : newline + 1);
}

// assimp's OFF reader reserves what the header declares before reading a face: a 60-byte file that
// claims a billion faces makes it allocate and touch gigabytes (the fuzzer's out-of-memory and
// time-outs). Every vertex takes at least 6 bytes ("0 0 0\n") and every face 4 ("1 0\n"), so counts
// the file's size cannot hold are refused here, at once. Files whose header this does not
// recognize are left to assimp.
void check_off_counts(const std::filesystem::path& path, const std::string& name) {
  if (lower_extension(path) != ".off") return;
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> tokens;  // the keyword and the three counts, comments skipped
  for (std::string line; tokens.size() < 4 && std::getline(in, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    for (std::string word; tokens.size() < 4 && words >> word;) tokens.push_back(word);
  }
  if (tokens.size() < 3 || tokens[0].size() < 3 || tokens[0].compare(tokens[0].size() - 3, 3, "OFF") != 0) return;
  // Leading digits, as assimp reads a count (it stops at the first other character); saturated.
  uint64_t counts[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string& t = tokens[static_cast<size_t>(k) + 1];
    if (t.empty() || !std::isdigit(static_cast<unsigned char>(t[0]))) return;
    for (size_t i = 0; i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])); ++i)
      counts[k] = std::min<uint64_t>(counts[k] * 10 + static_cast<uint64_t>(t[i] - '0'), uint64_t{1} << 60);
  }
  std::error_code error;
  const uintmax_t bytes = std::filesystem::file_size(path, error);
  if (error) return;
  const long double needed = 6.0L * counts[0] + 4.0L * counts[1];
  if (needed > static_cast<long double>(bytes))
    throw InputError(name + ": its OFF header declares " + std::to_string(counts[0]) + " vertices and " +
                     std::to_string(counts[1]) + " faces, more than its " + std::to_string(bytes) +
                     " bytes can hold (the file is cut short or malformed)");
}

// The OBJ text with every face corner reduced to its position index ("f 1/1/1 2/2/7" -> "f 1 2").
// Real exports (the YCB meshes among them) keep texture-coordinate references after stripping
// the coordinates themselves, which assimp rejects as "Invalid face index"; depth needs positions only.
std::string obj_with_positions_only(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("f ", 0) != 0) {
      out << line << '\n';
      continue;
    }
    std::istringstream corners(line.substr(2));
    std::string corner;
    out << 'f';
    while (corners >> corner) out << ' ' << corner.substr(0, corner.find('/'));
    out << '\n';
  }
  return out.str();
}

// The child's answer: vertex and triangle counts, then the coordinates and the indices.
std::string serialize(const Mesh& mesh) {
  const uint64_t counts[2] = {mesh.vertices.size(), mesh.triangles.size()};
  std::string out(reinterpret_cast<const char*>(counts), sizeof counts);
  for (const auto& v : mesh.vertices) out.append(reinterpret_cast<const char*>(v.data()), 3 * sizeof(float));
  for (const auto& t : mesh.triangles) out.append(reinterpret_cast<const char*>(t.data()), 3 * sizeof(int));
  return out;
}

Mesh deserialize(const std::string& bytes, const std::string& what) {
  uint64_t counts[2];
  if (bytes.size() < sizeof counts) throw InputError(what + ": the importer's answer is cut short");
  std::memcpy(counts, bytes.data(), sizeof counts);
  const uint64_t expected = sizeof counts + counts[0] * 3 * sizeof(float) + counts[1] * 3 * sizeof(int);
  if (counts[0] > bytes.size() || counts[1] > bytes.size() || expected != bytes.size())
    throw InputError(what + ": the importer's answer is cut short");
  Mesh mesh;
  mesh.vertices.resize(counts[0]);
  mesh.triangles.resize(counts[1]);
  const char* at = bytes.data() + sizeof counts;
  for (auto& v : mesh.vertices) {
    std::memcpy(v.data(), at, 3 * sizeof(float));
    at += 3 * sizeof(float);
  }
  for (auto& t : mesh.triangles) {
    std::memcpy(t.data(), at, 3 * sizeof(int));
    at += 3 * sizeof(int);
  }
  return mesh;
}

// The assimp part of loading, run in the child process: the raw triangle list, not yet welded.
Mesh import_with_assimp(const std::filesystem::path& path, double unit_scale, const std::string& name) {
  // No DefaultLogger is created, so assimp logs nowhere (the library must not print).
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), 0);
  std::string obj_text;  // must outlive the scene read from it
  if ((!scene || !has_polygons(*scene)) && is_obj(path)) {
    // Depending on the file, assimp fails or silently drops such faces: retry with positions only.
    const std::string first_error = scene ? "" : importer.GetErrorString();
    obj_text = obj_with_positions_only(path);
    scene = importer.ReadFileFromMemory(obj_text.data(), obj_text.size(), 0, "obj");
    if (!scene)
      throw InputError("cannot read " + name + ": " + (first_error.empty() ? importer.GetErrorString() : first_error));
  }
  if (!scene) throw InputError("cannot read " + name + ": " + importer.GetErrorString());
  // Checked before post-processing, which fails on such a scene with a message about orphaned meshes.
  if (!has_polygons(*scene)) throw InputError(name + " is empty: it has no triangles");
  check_triangle_limit(*scene, name);
  // ValidateDataStructure runs first and rejects out-of-range indices, which the other steps would follow;
  // PreTransformVertices bakes node transforms into the vertices; Triangulate splits polygons.
  scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                       aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (!scene) throw InputError("cannot read " + name + ": " + importer.GetErrorString());

  Mesh mesh;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) append_triangles(*scene->mMeshes[i], unit_scale, name, mesh);
  if (mesh.triangles.empty()) throw InputError(name + " is empty: it has no triangles");
  return mesh;
}

}  // namespace

std::chrono::milliseconds mesh_import_time_limit(uintmax_t file_bytes) {
  // Real meshes load at well over 10 MB/s here (the 2.4 MB bunny in 0.3 s): this is generous.
  return std::chrono::milliseconds(20'000 + static_cast<long long>(file_bytes / 500));
}

namespace {

// What both entry points check before assimp sees the file.
std::string checked_mesh_name(const std::filesystem::path& path, double unit_scale) {
  const std::string name = "mesh '" + path.string() + "'";
  if (!std::isfinite(unit_scale) || unit_scale <= 0)
    throw InputError(name + ": unit_scale must be finite and positive, got " + std::to_string(unit_scale));
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError("mesh file '" + path.string() + "' does not exist");
  if (!std::filesystem::is_regular_file(path, error))
    throw InputError("mesh file '" + path.string() + "' is not a file");
  check_ply_header(path, name);
  check_off_counts(path, name);
  return name;
}

Mesh welded_and_clean(Mesh mesh, const std::string& name) {
  weld(mesh, name);
  mesh.validate_and_clean(name);
  return mesh;
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path, double unit_scale, std::chrono::milliseconds time_limit) {
  const std::string name = checked_mesh_name(path, unit_scale);
  // assimp crashes, aborts or loops on some malformed files (the fuzzer finds many): it runs in a
  // child process, so that any of those becomes an InputError naming the file.
  Mesh mesh = deserialize(
      io::call_isolated([&] { return serialize(import_with_assimp(path, unit_scale, name)); }, time_limit, name), name);
  return welded_and_clean(std::move(mesh), name);
}

Mesh load_mesh_unguarded(const std::filesystem::path& path, double unit_scale) {
  const std::string name = checked_mesh_name(path, unit_scale);
  return welded_and_clean(import_with_assimp(path, unit_scale, name), name);
}

Mesh Mesh::load(const std::filesystem::path& path, double unit_scale) {
  std::error_code error;
  const uintmax_t bytes = std::filesystem::file_size(path, error);
  return load_mesh(path, unit_scale, mesh_import_time_limit(error ? 0 : bytes));
}

}  // namespace depthtrack
