// cl/ sources as programs receive them: includes inlined once, and DEPTHTRACK_KERNEL_DIR's files
// replacing the embedded ones of the same name (kernels edited or varied without a rebuild).
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <string>

#include "binary_cache_support.hpp"
#include "compute/kernel_sources.hpp"

using namespace depthtrack;

namespace {
size_t occurrences(const std::string& text, const std::string& word) {
  size_t count = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++count;
  return count;
}
}  // namespace

TEST_CASE("A kernel source inlines each included file once", "[kernel_sources]") {
  // rasterize.cl includes dt_prelude.h directly and through dt_quaternion.h, dt_state.h and others.
  const std::string source = compute::kernel_source("rasterize.cl");
  CHECK(source.find("#include \"") == std::string::npos);
  CHECK(occurrences(source, "#define DT_PIXEL_BOX_H") == 1);
  CHECK(occurrences(source, "__kernel DT_RESIDENCY void rasterize(") == 1);
}

TEST_CASE("DEPTHTRACK_KERNEL_DIR replaces embedded kernel files by name", "[kernel_sources]") {
  const auto folder = std::filesystem::temp_directory_path() / "depthtrack-kernel-dir-test";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  // A replaced header reaches every file that includes it; files absent from the folder stay embedded.
  test::write_all(folder / "dt_pixel_box.h", "/* replaced box header */\n");
  test::write_all(folder / "variant.cl", "#include \"dt_pixel_box.h\"\n#include \"dt_prelude.h\"\nvariant body\n");
  const std::string embedded_prelude = compute::kernel_source("dt_prelude.h");
  {
    test::ScopedEnv dir("DEPTHTRACK_KERNEL_DIR", folder.c_str());
    const std::string rasterize = compute::kernel_source("rasterize.cl");
    CHECK(occurrences(rasterize, "/* replaced box header */") == 1);
    CHECK(rasterize.find("DT_PIXEL_BOX_H") == std::string::npos);
    const std::string variant = compute::kernel_source("variant.cl");
    CHECK(variant == "/* replaced box header */\n" + embedded_prelude + "variant body\n");
  }
  // Unset, the embedded files again (and a file only the folder had is unknown).
  CHECK(occurrences(compute::kernel_source("rasterize.cl"), "#define DT_PIXEL_BOX_H") == 1);
  CHECK_THROWS_WITH(compute::kernel_source("variant.cl"), Catch::Contains("not embedded"));
  std::filesystem::remove_all(folder);
}

TEST_CASE("DEPTHTRACK_KERNEL_DIR naming no folder is an error naming it", "[kernel_sources]") {
  test::ScopedEnv dir("DEPTHTRACK_KERNEL_DIR", "/nonexistent/depthtrack-kernels");
  CHECK_THROWS_AS(compute::kernel_source("rasterize.cl"), BackendError);
  CHECK_THROWS_WITH(compute::kernel_source("rasterize.cl"),
                    Catch::Contains("DEPTHTRACK_KERNEL_DIR") && Catch::Contains("/nonexistent/depthtrack-kernels"));
}
