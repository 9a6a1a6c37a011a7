#pragma once
// Renders the mesh in many poses at once into a pose atlas of metric z-depth tiles (R32F), with
// the reference rasterizer's conventions (src/reference/rasterizer.hpp): one instanced draw call
// per page, each instance placed in its tile and clipped to it. The GlContext must outlive the
// renderer; every call makes it current on the calling thread.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <span>
#include <vector>

#include "atlas/atlas_layout.hpp"
#include "atlas/gl/gl_context.hpp"

namespace depthtrack::render {

struct AtlasOptions {
  int max_texture_size = 0;  // page size limit in pixels; 0: the context's; smaller forces pages (tests)
  // Depth-test the exact plane depth (gl_FragDepth) rather than the rasterizer's interpolated one.
  // Either way the stored depth is exact; the two differ only where surfaces meet within the
  // interpolation error (~1e-6 relative), and writing gl_FragDepth costs early depth rejection.
  bool exact_depth_test = true;
  // Texels a texture buffer may hold (triangle planes, poses); 0: the context's
  // GL_MAX_TEXTURE_BUFFER_SIZE; smaller makes the limit testable with small meshes.
  long long max_buffer_texels = 0;
};

// One page's GL objects, for the hand-off to compute: colour is GL_TEXTURE_2D, GL_R32F.
struct AtlasPage {
  AtlasPageLayout layout;
  GLuint color_texture = 0, depth_texture = 0, framebuffer = 0;
};

class AtlasRenderer {
 public:
  AtlasRenderer(GlContext& context, const Mesh& mesh, const Camera& camera, double near, double far,
                AtlasOptions options = {});
  ~AtlasRenderer();
  AtlasRenderer(const AtlasRenderer&) = delete;
  AtlasRenderer& operator=(const AtlasRenderer&) = delete;

  // Draws every pose (camera_from_object) into its tile; uncovered pixels hold 0.
  void render(std::span<const Pose> poses);
  // Copies the last render's tiles into out in pose order, each row-major width x height.
  void read_back(std::span<float> out);

  // The pieces of render() for a compute hand-off: reserve() sizes the pages and the pose buffer
  // for `tiles` poses (nothing changes when the count does not); the pose buffer then holds one
  // particle state per tile (DT_STATE_STRIDE floats, cl/dt_state.h: translation, quaternion, ...),
  // written by upload_states() or by the compute device through interop; draw() renders them all.
  void reserve(int tiles);
  void upload_states(std::span<const float> states);
  void draw();
  // Waits until GL has executed everything issued (glFinish).
  void finish();
  GLuint pose_buffer() const { return pose_buffer_; }
  // Reads one page as it lies (page width x height floats, row-major, image rows not flipped).
  void read_page(const AtlasPage& page, std::span<float> out);
  // The same into a GL buffer at a byte offset (a copy on the GPU; glFinish or finish() before
  // another API reads the buffer).
  void read_page_into(const AtlasPage& page, GLuint pack_buffer, size_t byte_offset);

  int tile_count() const { return tiles_; }
  const AtlasLayout& layout() const { return layout_; }
  const std::vector<AtlasPage>& pages() const { return pages_; }
  GlContext& context() { return context_; }

 private:
  void release_pages();
  void check(const char* what);

  GlContext& context_;
  const GlFunctions& gl_;
  Camera camera_;
  int max_size_ = 0;
  long long max_buffer_texels_ = 0;
  GLsizei index_count_ = 0;
  bool cull_back_faces_ = false;  // bounds_solid_outward(mesh): triangles facing away are never nearest
  GLuint program_ = 0, vertex_array_ = 0, vertex_buffer_ = 0, index_buffer_ = 0;
  GLuint pose_buffer_ = 0, pose_texture_ = 0, plane_buffer_ = 0, plane_texture_ = 0;
  GLint first_pose_location_ = -1, tiles_per_row_location_ = -1, page_size_location_ = -1;
  int tiles_ = 0;
  AtlasLayout layout_;
  std::vector<AtlasPage> pages_;
  std::vector<float> states_;   // render()'s poses as particle states
  std::vector<float> staging_;  // one page, read back before it is scattered into pose order
};

}  // namespace depthtrack::render
