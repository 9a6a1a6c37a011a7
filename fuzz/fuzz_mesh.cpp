// Mesh::load's path on arbitrary bytes named *.FUZZ_MESH_EXTENSION.
// The libFuzzer binary (FUZZ_MESH_UNGUARDED) calls the importer in this process, so that libFuzzer
// sees the parser itself at thousands of inputs a second, with its -timeout and -rss_limit_mb as the
// hang and memory guard: every crash or hang it reports is assimp's (or ours) on that input.
// The replay binary (the ctest regression test) goes through the product's guard instead, the child
// process with a short limit, because the corpus holds files that crash assimp: for it, each must
// come back as an InputError in bounded time.
#include <depthtrack/error.hpp>

#include "fuzz_input.hpp"
#include "io/mesh_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = depthtrack::fuzz::write_input("mesh." FUZZ_MESH_EXTENSION, data, size);
  try {
#ifdef FUZZ_MESH_UNGUARDED
    const auto mesh = depthtrack::load_mesh_unguarded(path, 1.0);
#else
    const auto mesh = depthtrack::load_mesh(path, 1.0, std::chrono::milliseconds(1000));
#endif
    (void)mesh.centre();
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
