// The kernel renderer's rasterization inside weigh (cl/render_weigh.cl) against rasterize.cl followed by
// weigh.cl: the same tiles, log-likelihoods and occlusion states bit for bit (against whole tiles, the
// log-likelihoods to float rounding), in every occlusion mode.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>

#include "atlas/atlas_layout.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "core/mesh_topology.hpp"
#include "device_support.hpp"
#include "dt_state.h"
#include "dt_time_index.h"
#include "filter/device_filter.hpp"
#include "model/kernel_params.hpp"
#include "model/particle.hpp"
#include "model/particle_packing.hpp"
#include "reference/rasterizer.hpp"

using namespace depthtrack;

namespace {
// Where two atlases of tiles `width` pixels wide and `pixels` in all differ: the count and the first such pixel
// with both values ("equal" where none does), so that a failure says which particle and pixel, not two whole
// atlases.
std::string atlas_difference(const std::vector<float>& a, const std::vector<float>& b, size_t pixels,
                             size_t width = 80) {
  if (a.size() != b.size()) return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
  size_t differ = 0, first = 0;
  for (size_t k = 0; k < a.size(); ++k)
    if (std::memcmp(&a[k], &b[k], sizeof(float)) != 0 && differ++ == 0) first = k;
  if (differ == 0) return "equal";
  char text[200];
  std::snprintf(text, sizeof text, "%zu pixels differ; the first: particle %zu, pixel (%zu, %zu): %.9g against %.9g",
                differ, first / pixels, first % pixels % width, first % pixels / width, static_cast<double>(a[first]),
                static_cast<double>(b[first]));
  return text;
}

// Each triangle cut into four at its edges' midpoints (shared between the two triangles of an edge, so a
// closed mesh stays closed and wound as it was), `times` times: the same surface in 4^times as many triangles.
Mesh subdivided(Mesh mesh, int times) {
  for (int round = 0; round < times; ++round) {
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = midpoints.try_emplace(key, static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(0.5f * (mesh.vertices[a] + mesh.vertices[b]));
      return it->second;
    };
    std::vector<Eigen::Vector3i> finer;
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    mesh.triangles = std::move(finer);
  }
  return mesh;
}
}  // namespace

TEST_CASE("rasterizing inside weigh equals rasterize then weigh, bit for bit", "[device][kernels][render]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const size_t pixels = 4800, count = 24;
  REQUIRE(renders_inside_weigh(Renderer::Kernel, pixels, 48 * 1024));
  // The built-in box in 1,536 triangles: more than a chunk of the list (512), so that each work-item's
  // corners loaded ahead cross from one chunk into the next.
  const Mesh mesh = subdivided(builtin_demo_mesh(), 3);
  REQUIRE(mesh.triangles.size() == 1536);
  REQUIRE(bounds_solid_outward(mesh));
  TrackerConfig config;
  const Pose truth({0, 0, 0.8}, rotation_exp(Eigen::Vector3d(0.4, 0.5, 0.1)));
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  // Observed: the object with an occluding band and missing pixels; particles around it.
  std::vector<float> observed(pixels);
  reference::Rasterizer(mesh, camera, config.near_plane, config.observation.max_depth).render(truth, observed);
  for (size_t k = 0; k < pixels; ++k) {
    if (observed[k] == 0) observed[k] = 1.5f;
    if (k % 80 >= 30 && k % 80 < 36) observed[k] = 0.55f;
    if (k % 13 == 0) observed[k] = NAN;
  }
  std::vector<model::ParticleState> particles(count);
  for (size_t i = 0; i < count; ++i)
    particles[i].pose =
        model::move_about_centre(truth, Eigen::Vector3d::Zero(),
                                 Eigen::Vector3d(0.02 * unit(rng) - 0.01, 0.02 * unit(rng) - 0.01, 0.3 * unit(rng)),
                                 Eigen::Vector3d(0.2 * unit(rng), 0.2 * unit(rng), 0.2 * unit(rng)));
  // One pose crosses the near plane (0.05 m): its triangles are cut, and a group keeping projected
  // vertices (DT_SHARED_POINTS) draws it as one that does not.
  particles[count - 1].pose = Pose({0.0, 0.0, 0.07}, rotation_exp(Eigen::Vector3d(0.0, 0.5, 0.0)));
  std::vector<float> occlusion(count * pixels);
  std::vector<uint16_t> times(count * pixels);
  std::vector<unsigned> parents(count);
  for (auto& p : occlusion) p = unit(rng);
  for (auto& t : times) t = static_cast<uint16_t>(std::min(31.0f, 32 * unit(rng)));
  for (size_t i = 0; i < count; ++i) parents[i] = static_cast<unsigned>((i * 7) % count / 3);
  std::vector<float> frame_times(DT_TIME_TABLE, 0.0f);
  for (unsigned f = 0; f < 32; ++f) frame_times[f] = 0.02f * static_cast<float>(f);
  const float now = 0.9f, dt = 0.033f;
  const unsigned now_index = 40;

  const MeshBuffers mesh_buffers(*q, mesh);
  const dt_camera cam = model::camera_params(camera, config, mesh_buffers.cull_back_faces);
  const dt_model m = model::model_params(config);
  const auto layout = render::AtlasLayout::particle_major(static_cast<int>(count), 80, 60);
  const auto range = compute::NdRange::linear(count * 128, 128);
  for (const int mode : {0, 1, 2}) {
    INFO("occlusion mode " << mode);
    const std::vector<std::string> defines = {"DT_GROUP_SIZE=128", "DT_OCCLUSION=" + std::to_string(mode)};
    auto build = [&](const std::string& file, std::vector<std::string> d) {
      return q->build(file, compute::kernel_source(file), d);
    };
    auto raster_program = build("rasterize.cl", {"DT_GROUP_SIZE=128"});
    auto weigh_program = build("weigh.cl", defines);
    // Each triangle projecting its corners, and the group projecting each vertex once and listing the
    // triangles that draw (the mesh's vertices in work-group memory).
    const size_t points = render_weigh_shared_points(pixels, mesh_buffers.vertex_count(), 48 * 1024);
    REQUIRE(points == mesh_buffers.vertex_count());
    auto fused_program = build("render_weigh.cl", {defines[0], defines[1], "DT_TILE_PIXELS=4800"});
    auto listed_program =
        build("render_weigh.cl", {defines[0], defines[1], "DT_TILE_PIXELS=4800",
                                  "DT_SHARED_POINTS=" + std::to_string(points), "DT_PROPAGATE_INSIDE=1"});
    auto rasterize = raster_program->kernel("rasterize");
    auto weigh = weigh_program->kernel("weigh");
    // And with the host's promise that the state window is the whole image (DT_WHOLE_IMAGE_STATE).
    auto whole_program =
        build("render_weigh.cl", {defines[0], defines[1], "DT_TILE_PIXELS=4800",
                                  "DT_SHARED_POINTS=" + std::to_string(points), "DT_WHOLE_IMAGE_STATE=1"});
    // And with a tile of 5 rows (400 pixels): each pose's box drawn and weighed in bands of rows.
    auto banded_program = build("render_weigh.cl", {defines[0], defines[1], "DT_TILE_PIXELS=400"});
    auto banded_listed_program = build("render_weigh.cl", {defines[0], defines[1], "DT_TILE_PIXELS=400",
                                                           "DT_SHARED_POINTS=" + std::to_string(points)});
    auto corners = fused_program->kernel("render_weigh"), listed = listed_program->kernel("render_weigh"),
         whole = whole_program->kernel("render_weigh"), banded = banded_program->kernel("render_weigh"),
         banded_listed = banded_listed_program->kernel("render_weigh");
    compute::Kernel* fused = corners.get();

    auto propagate_program = build("propagate.cl", {"DT_GROUP_SIZE=128"});
    auto propagate = propagate_program->kernel("propagate");
    const dt_motion motion = model::motion_params(model::motion_step(config.motion, dt), Eigen::Vector3d(0.01, 0, 0));
    const unsigned seed_lo = 5, seed_hi = 1, frame = 3;

    struct Run {
      std::vector<float> atlas, ll, lw, occlusion, table, states;
      std::vector<uint16_t> times;
    };
    enum class Motion { None, Kernel, Inside };  // no motion step; propagate.cl first; render_weigh's own
    // inside: render_weigh; else rasterize, boxed or not, then weigh.
    auto run = [&](bool inside, unsigned keep_atlas, const dt_window& win, unsigned boxed = 0,
                   Motion step = Motion::None) {
      const size_t rows = count * win.width * win.height;
      compute::Buffer<float> states(*q, count * DT_STATE_STRIDE), obs(*q, pixels), occ_from(*q, rows), occ_to(*q, rows),
          table(*q, DT_TIME_TABLE), ll(*q, count), lw(*q, count), atlas(*q, layout.floats());
      compute::Buffer<uint16_t> t_from(*q, rows), t_to(*q, rows);
      compute::Buffer<unsigned> parent_buffer(*q, count), boxes(*q, 4 * count);
      states.upload(pack_particles(particles));
      obs.upload(observed);
      occ_from.upload(std::vector<float>(occlusion.begin(), occlusion.begin() + static_cast<std::ptrdiff_t>(rows)));
      occ_to.upload(std::vector<float>(rows, -1.0f));
      t_from.upload(std::vector<uint16_t>(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(rows)));
      t_to.upload(std::vector<uint16_t>(rows, 7));
      table.upload(frame_times);
      lw.upload(std::vector<float>(count, 2.0f));
      atlas.upload(std::vector<float>(layout.floats(), -3.0f));
      parent_buffer.upload(parents);
      if (step == Motion::Kernel)
        q->launch(*propagate, compute::NdRange::linear(64, 64), states, static_cast<unsigned>(count), seed_lo, seed_hi,
                  frame, motion);
      if (inside) {
        q->launch(*fused, range, states, mesh_buffers.vertices, mesh_buffers.triangles, mesh_buffers.planes,
                  mesh_buffers.triangle_count(), mesh_buffers.vertex_count(), cam, obs, parent_buffer, occ_from, t_from,
                  occ_to, t_to, table, ll, lw, m, now, now_index, dt, atlas, keep_atlas, win,
                  static_cast<unsigned>(step == Motion::Inside), seed_lo, seed_hi, frame, motion);
      } else {
        q->launch(*rasterize, range, states, mesh_buffers.vertices, mesh_buffers.triangles, mesh_buffers.planes,
                  mesh_buffers.triangle_count(), mesh_buffers.vertex_count(), cam, layout.kernel_args(), atlas, boxes,
                  boxed, 0u);
        q->launch(*weigh, range, atlas, obs, parent_buffer, occ_from, t_from, occ_to, t_to, table, ll, lw,
                  static_cast<unsigned>(pixels), m, now, now_index, dt, layout.kernel_args(), win, boxes, boxed, 0u);
      }
      q->finish();
      return Run{atlas.download(), ll.download(),     lw.download(),  occ_to.download(),
                 table.download(), states.download(), t_to.download()};
    };
    // The whole image's state, and a 16x12 state window (cutting the object) moved by (3, 2) since the rows were
    // written.
    for (const dt_window& win :
         {dt_window{0, 0, 0, 0, 80, 60, 80, 60, 80, 0.1f}, dt_window{34, 26, 31, 24, 16, 12, 16, 12, 80, 0.1f}}) {
      INFO("state window " << win.width << "x" << win.height);
      fused = corners.get();
      const Run apart = run(false, 0, win), inside = run(true, 1, win), unkept = run(true, 0, win),
                boxed = run(false, 0, win, 1);
      fused = listed.get();
      const Run listed_inside = run(true, 1, win), listed_unkept = run(true, 0, win);
      fused = banded.get();
      const Run banded_inside = run(true, 1, win), banded_unkept = run(true, 0, win);
      fused = banded_listed.get();
      const Run banded_listed_inside = run(true, 1, win);
      std::vector<const Run*> drawn_inside = {&inside,        &unkept,        &listed_inside,       &listed_unkept,
                                              &banded_inside, &banded_unkept, &banded_listed_inside};
      Run whole_image;
      if (win.width == 80 && win.height == 60) {  // the promise holds only for the whole image's window
        fused = whole.get();
        whole_image = run(true, 0, win);
        drawn_inside.push_back(&whole_image);
      }
      for (size_t i = 0; i < count; ++i) {  // every particle is in view
        size_t covered = 0;
        for (size_t k = 0; k < pixels; ++k) covered += apart.atlas[i * pixels + k] > 0;
        CHECK(covered >= 20);
      }
      CHECK(atlas_difference(inside.atlas, apart.atlas, pixels) == "equal");
      CHECK(atlas_difference(listed_inside.atlas, apart.atlas, pixels) == "equal");
      CHECK(atlas_difference(banded_inside.atlas, apart.atlas, pixels) == "equal");
      CHECK(atlas_difference(banded_listed_inside.atlas, apart.atlas, pixels) == "equal");
      for (size_t i = 0; i < count; ++i) {  // the bands were needed: a box taller than the tile's 5 rows
        size_t rows = 0;
        for (size_t v = 0; v < 60; ++v) {
          bool drawn = false;
          for (size_t u = 0; u < 80; ++u) drawn = drawn || apart.atlas[i * pixels + v * 80 + u] > 0;
          rows += drawn;
        }
        CHECK(rows > 5);
      }
      CHECK(unkept.atlas == std::vector<float>(layout.floats(), -3.0f));  // not stored unless asked
      // Rasterized only in each pose's box (the rest of the tile left as it was): the same tiles inside
      // the boxes, and weigh takes the rest as empty.
      size_t stale = 0;
      for (size_t k = 0; k < boxed.atlas.size(); ++k) {
        stale += boxed.atlas[k] == -3.0f;
        if (boxed.atlas[k] != -3.0f) REQUIRE(boxed.atlas[k] == apart.atlas[k]);
        if (boxed.atlas[k] == -3.0f) REQUIRE(apart.atlas[k] == 0.0f);
      }
      CHECK(stale > boxed.atlas.size() / 2);  // most of each tile lies outside the pose's box
      // Drawn inside weigh, and kept or not: bit for bit what boxed rasterize + weigh give (both visit the
      // rectangle around the pose's box and the window, in the same order).
      for (const Run* r : drawn_inside) {
        CHECK(r->ll == boxed.ll);
        CHECK(r->lw == boxed.lw);
        CHECK(r->occlusion == boxed.occlusion);
        CHECK(r->times == boxed.times);
        CHECK(r->table == boxed.table);
      }
      // Unboxed, weigh visits the whole image: the same terms added in another order (float rounding in
      // the sums), the same states.
      for (size_t i = 0; i < count; ++i) {
        CHECK(boxed.ll[i] == Approx(apart.ll[i]).epsilon(1e-5).margin(1e-4));
        CHECK(boxed.lw[i] == Approx(apart.lw[i]).epsilon(1e-5).margin(1e-4));
      }
      CHECK(boxed.occlusion == apart.occlusion);
      CHECK(boxed.times == apart.times);
      CHECK(boxed.table == apart.table);
      // Each group moving its own particle first (the filter's frame, one launch fewer): the states and
      // sums propagate.cl followed by render_weigh give, bit for bit; and the particles did move.
      fused = listed.get();
      const Run moved_first = run(true, 1, win, 0, Motion::Kernel), moved_inside = run(true, 1, win, 0, Motion::Inside);
      CHECK(moved_inside.states == moved_first.states);
      CHECK(moved_inside.states != inside.states);
      CHECK(moved_inside.atlas == moved_first.atlas);
      CHECK(moved_inside.ll == moved_first.ll);
      CHECK(moved_inside.occlusion == moved_first.occlusion);
      CHECK(moved_inside.ll != inside.ll);
    }
  }
}

TEST_CASE(
    "render_weigh and rasterize ask for as many groups a unit as its memory holds, within 64 registers a "
    "work-item",
    "[render]") {
  compute::DeviceInfo h200;  // cuDeviceGetAttribute's values on an H200
  h200.local_memory_per_unit = 233472;
  h200.local_memory_reserved = 1024;
  h200.registers_per_unit = 65536;
  // 80x60 with the handset's 423 points: 19,200 (tile) + 2,560 (reduction) + 3,384 (points) + 4,100 (list
  // of 512 and count) = 29,244 bytes, 30,268 with the reserve: 7 fit in 233,472 (65,536 / (128 x 64) = 8).
  CHECK(render_weigh_resident_groups(4800, 423, h200) == 7);
  // No points kept (a 16k-triangle mesh): 21,760 + 1,024 bytes, 10 fit; the registers' 8 decide.
  CHECK(render_weigh_resident_groups(4800, 0, h200) == 8);
  // A unit of 64 KiB holds 2 of the first.
  compute::DeviceInfo small = h200;
  small.local_memory_per_unit = 65536;
  CHECK(render_weigh_resident_groups(4800, 423, small) == 2);
  // A tile larger than the unit's memory still asks for one.
  small.local_memory_per_unit = 16384;
  CHECK(render_weigh_resident_groups(4800, 0, small) == 1);
  // OpenCL says nothing of units: no hint.
  CHECK(render_weigh_resident_groups(4800, 423, compute::DeviceInfo{}) == 0);
  // The tile of half the image's rows (80x60: 2,400 pixels) with the simplified mug's 1,600 points: 9,600 +
  // 2,560 + 12,800 + 4,100 + 1,024 = 30,084 bytes, 7 fit; the whole image's tile: 39,684, 5. So the mug
  // gets the half tile; the handset's 423 points fit 7 beside the whole tile and 8 beside the half (the
  // registers' 8 decide there): one group more, so it keeps the whole.
  CHECK(render_weigh_resident_groups(2400, 1600, h200) == 7);
  CHECK(render_weigh_resident_groups(4800, 1600, h200) == 5);
  CHECK(render_weigh_resident_groups(2400, 423, h200) == 8);
  h200.local_memory = 48 * 1024;
  const RenderWeighLayout mug = render_weigh_layout(80, 60, 1600, h200),
                          handset = render_weigh_layout(80, 60, 423, h200);
  CHECK(mug.tile_pixels == 2400);
  CHECK(mug.shared_points == 1600);
  CHECK(mug.resident_groups == 7);
  CHECK(handset.tile_pixels == 4800);
  CHECK(handset.resident_groups == 7);
  // 59 rows: half is 30 of them.
  CHECK(render_weigh_layout(80, 59, 1600, h200).tile_pixels == 2400);
  // 4,000 points (32,000 bytes) fit beside the half tile's 9,600 within CUDA's 48 KiB, not beside the whole
  // image's 19,200: the half tile, which keeps them.
  const RenderWeighLayout fine = render_weigh_layout(80, 60, 4000, h200);
  CHECK(fine.tile_pixels == 2400);
  CHECK(fine.shared_points == 4000);
  CHECK(render_weigh_shared_points(4800, 4000, 48 * 1024) == 0);
  // OpenCL says nothing of units: the whole image's tile, as before.
  compute::DeviceInfo opencl;
  opencl.local_memory = 48 * 1024;
  CHECK(render_weigh_layout(80, 60, 1600, opencl).tile_pixels == 4800);
  // rasterize's 2,560 bytes (+ 1,024): 65 fit in memory, the registers allow 8; 256 work-items a group, 4.
  CHECK(rasterize_definitions(128, h200) == std::vector<std::string>{"DT_GROUP_SIZE=128", "DT_RESIDENT_GROUPS=8"});
  CHECK(rasterize_definitions(256, h200) == std::vector<std::string>{"DT_GROUP_SIZE=256", "DT_RESIDENT_GROUPS=4"});
  CHECK(rasterize_definitions(128, compute::DeviceInfo{}).back() == "DT_RESIDENT_GROUPS=0");
}

TEST_CASE("render_weigh moves the particles itself for small clouds drawn inside it only", "[render]") {
  const size_t local = 48 * 1024;  // a GPU's work-group memory; 80x60's tile fits, 160x120's does not
  CHECK(propagates_inside_weigh(Renderer::Kernel, 4800, local, 2000));
  CHECK(propagates_inside_weigh(Renderer::Kernel, 4800, local, kFusedLaunchParticles));
  // Larger clouds keep propagate.cl's launch and render_weigh without the moving block.
  CHECK_FALSE(propagates_inside_weigh(Renderer::Kernel, 4800, local, kFusedLaunchParticles + 1));
  // Drawn apart (the GL or host atlas, or a tile beyond work-group memory), weigh moves nothing.
  CHECK_FALSE(propagates_inside_weigh(Renderer::Gl, 4800, local, 2000));
  CHECK_FALSE(propagates_inside_weigh(Renderer::Cpu, 4800, local, 2000));
  CHECK_FALSE(propagates_inside_weigh(Renderer::Kernel, 160 * 120, local, 2000));
}
