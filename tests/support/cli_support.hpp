#pragma once
// Helpers of the command-line tests: a small sequence with its mesh file, CSV reading.
#include <depthtrack/synth.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace depthtrack::test {

// Writes mesh as an OBJ file, coordinates multiplied by scale.
inline void write_obj(const std::filesystem::path& path, const Mesh& mesh, double scale = 1.0) {
  std::ofstream obj(path);
  obj.precision(9);
  for (const auto& v : mesh.vertices)
    obj << "v " << scale * v.x() << " " << scale * v.y() << " " << scale * v.z() << "\n";
  for (const auto& t : mesh.triangles) obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

// A short synthetic sequence of the built-in object at 160x120 in dir/seq, and the built-in mesh as
// dir/object.obj (track takes a mesh file); returns dir, a fresh folder named name.
inline std::filesystem::path write_cli_sequence(const std::string& name, int frames = 6) {
  const auto dir = temp_dir(name);
  SynthConfig c;
  c.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  c.frames = frames;
  write_synthetic_sequence(dir / "seq", builtin_demo_mesh(), c);
  write_obj(dir / "object.obj", builtin_demo_mesh());
  return dir;
}

inline std::vector<std::string> lines_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The whole file as text ("" when it cannot be read).
inline std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> cells_of(const std::string& line) {
  std::stringstream row(line);
  std::vector<std::string> cells;
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  return cells;
}

}  // namespace depthtrack::test
