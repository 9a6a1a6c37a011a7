#pragma once
// A sequence on disk for the command-line tests: the built-in object, synthesized, and its mesh as an OBJ.
#include <depthtrack/synth.hpp>
#include <fstream>
#include <string>

#include "support.hpp"

namespace depthtrack::test {

// A short synthetic sequence of the built-in object at 160x120, written once per test.
inline std::filesystem::path write_sequence(const std::string& name, int frames = 6) {
  const auto dir = test::temp_dir(name);
  SynthConfig c;
  c.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  c.frames = frames;
  write_synthetic_sequence(dir / "seq", builtin_demo_mesh(), c);
  // The built-in mesh as an OBJ, since track takes a mesh file.
  std::ofstream obj(dir / "object.obj");
  const Mesh mesh = builtin_demo_mesh();
  for (const auto& v : mesh.vertices) obj << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : mesh.triangles) obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return dir;
}

}  // namespace depthtrack::test
