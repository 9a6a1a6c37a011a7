// Mesh::load (assimp, isolated in a child process) on arbitrary bytes named *.FUZZ_MESH_EXTENSION.
// A crash, abort or hang of assimp must come back as an InputError; the limit is short here so
// that hanging inputs cost one second, not Mesh::load's twenty.
#include <depthtrack/error.hpp>

#include "fuzz_input.hpp"
#include "io/mesh_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = depthtrack::fuzz::write_input("mesh." FUZZ_MESH_EXTENSION, data, size);
  try {
    const auto mesh = depthtrack::load_mesh(path, 1.0, std::chrono::milliseconds(1000));
    (void)mesh.centre();
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
