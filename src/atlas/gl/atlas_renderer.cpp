#include "atlas/gl/atlas_renderer.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>
#include <string>

#include "atlas/gl/gl_program.hpp"
#include "atlas/triangle_planes.hpp"
#include "core/mesh_topology.hpp"
#include "core/pose_state.hpp"
#include "dt_state.h"

namespace depthtrack::render {

AtlasRenderer::AtlasRenderer(GlContext& context, const Mesh& mesh, const Camera& camera, double near, double far,
                             AtlasOptions options)
    : context_(context), gl_(context.gl()), camera_(camera) {
  camera.validate();
  if (!(near > 0 && far > near)) throw InputError("atlas renderer needs 0 < near < far");
  if (mesh.vertices.empty() || mesh.triangles.empty()) throw InputError("atlas renderer needs a mesh with triangles");
  cull_back_faces_ = bounds_solid_outward(mesh);
  max_size_ = options.max_texture_size > 0 ? std::min(options.max_texture_size, context.max_render_size())
                                           : context.max_render_size();
  context_.make_current();
  GLint gl_buffer_texels = 0;
  gl_.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &gl_buffer_texels);
  max_buffer_texels_ = options.max_buffer_texels > 0 ? options.max_buffer_texels : gl_buffer_texels;
  // One plane texel per triangle: a larger mesh cannot be drawn by this GL at all.
  if (static_cast<long long>(mesh.triangles.size()) > max_buffer_texels_)
    throw InputError("the mesh has " + std::to_string(mesh.triangles.size()) +
                     " triangles, more than this GL can draw (GL_MAX_TEXTURE_BUFFER_SIZE " +
                     std::to_string(max_buffer_texels_) + " texels, one per triangle); simplify the mesh");
  program_ = build_program(
      gl_, "atlas.vert", "atlas.frag",
      options.exact_depth_test ? std::vector<std::string>{"DT_EXACT_DEPTH_TEST"} : std::vector<std::string>{});

  // Mesh: Eigen's Vector3f / Vector3i are packed, so the vectors upload as they are.
  gl_.GenVertexArrays(1, &vertex_array_);
  gl_.BindVertexArray(vertex_array_);
  gl_.GenBuffers(1, &vertex_buffer_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(Eigen::Vector3f)),
                 mesh.vertices.data(), GL_STATIC_DRAW);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
  gl_.EnableVertexAttribArray(0);
  gl_.GenBuffers(1, &index_buffer_);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);  // recorded in the vertex array
  gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(Eigen::Vector3i)),
                 mesh.triangles.data(), GL_STATIC_DRAW);
  index_count_ = static_cast<GLsizei>(mesh.triangles.size() * 3);
  gl_.BindVertexArray(0);

  // Triangle planes for atlas.frag's exact depth.
  const std::vector<float> planes = triangle_planes(mesh);
  gl_.GenBuffers(1, &plane_buffer_);
  gl_.BindBuffer(GL_TEXTURE_BUFFER, plane_buffer_);
  gl_.BufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(planes.size() * sizeof(float)), planes.data(),
                 GL_STATIC_DRAW);
  gl_.GenTextures(1, &plane_texture_);
  gl_.BindTexture(GL_TEXTURE_BUFFER, plane_texture_);
  gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, plane_buffer_);

  // Poses: particle states in a texture buffer, readable by gl_InstanceID in GLSL 330 on every GL
  // this runs on. atlas.vert reads the translation and quaternion at these offsets.
  static_assert(DT_STATE_STRIDE == 16 && DT_TX == 0 && DT_QW == 3, "atlas.vert reads cl/dt_state.h's layout");
  gl_.GenBuffers(1, &pose_buffer_);
  gl_.BindBuffer(GL_TEXTURE_BUFFER, pose_buffer_);
  gl_.BufferData(GL_TEXTURE_BUFFER, DT_STATE_STRIDE * sizeof(float), nullptr, GL_STREAM_DRAW);
  gl_.GenTextures(1, &pose_texture_);
  gl_.BindTexture(GL_TEXTURE_BUFFER, pose_texture_);
  gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, pose_buffer_);

  // Constant uniforms. OpenGL's mapping sends z = near to clip z = -w and z = far to +w, so the
  // clipper removes what the reference clips (z < near) and discards (z > far).
  gl_.UseProgram(program_);
  auto location = [this](const char* name) { return gl_.GetUniformLocation(program_, name); };
  gl_.Uniform1i(location("u_poses"), 0);
  gl_.Uniform1i(location("u_planes"), 1);
  gl_.Uniform2f(location("u_tile_size"), static_cast<float>(camera.width), static_cast<float>(camera.height));
  gl_.Uniform4f(location("u_intrinsics"), static_cast<float>(camera.fx), static_cast<float>(camera.fy),
                static_cast<float>(camera.cx), static_cast<float>(camera.cy));
  gl_.Uniform2f(location("u_depth_map"), static_cast<float>((far + near) / (far - near)),
                static_cast<float>(-2.0 * far * near / (far - near)));
  gl_.Uniform1f(location("u_inverse_far"), static_cast<float>(1.0 / far));
  first_pose_location_ = location("u_first_pose");
  tiles_per_row_location_ = location("u_tiles_per_row");
  page_size_location_ = location("u_page_size");
  gl_.UseProgram(0);
  check(
      ("setting up the atlas renderer for a mesh of " + std::to_string(mesh.triangles.size()) + " triangles").c_str());
}

AtlasRenderer::~AtlasRenderer() {
  try {
    context_.make_current();
  } catch (...) {
    return;  // the context is gone: so are its objects
  }
  release_pages();
  const GLuint textures[] = {pose_texture_, plane_texture_};
  gl_.DeleteTextures(2, textures);
  const GLuint buffers[] = {pose_buffer_, plane_buffer_, vertex_buffer_, index_buffer_};
  gl_.DeleteBuffers(4, buffers);
  gl_.DeleteVertexArrays(1, &vertex_array_);
  gl_.DeleteProgram(program_);
}

void AtlasRenderer::check(const char* what) {
  const GLenum error = gl_.GetError();
  if (error != GL_NO_ERROR) throw BackendError(std::string(what) + ": " + gl_error_name(error));
}

void AtlasRenderer::release_pages() {
  for (AtlasPage& p : pages_) {
    const GLuint textures[] = {p.color_texture, p.depth_texture};
    gl_.DeleteTextures(2, textures);
    gl_.DeleteFramebuffers(1, &p.framebuffer);
  }
  pages_.clear();
}

void AtlasRenderer::reserve(int tiles) {
  if (tiles <= 0) throw InputError("atlas renderer: no poses to render");
  if (tiles == tiles_ && !pages_.empty()) return;
  context_.make_current();
  if (static_cast<long long>(tiles) * (DT_STATE_STRIDE / 4) > max_buffer_texels_)
    throw InputError(std::to_string(tiles) + " poses exceed this GL's pose buffer (GL_MAX_TEXTURE_BUFFER_SIZE " +
                     std::to_string(max_buffer_texels_) + " texels, " + std::to_string(DT_STATE_STRIDE / 4) +
                     " per pose)");
  AtlasLayout layout = AtlasLayout::make(tiles, camera_.width, camera_.height, max_size_);
  release_pages();
  tiles_ = 0;
  gl_.BindBuffer(GL_TEXTURE_BUFFER, pose_buffer_);
  gl_.BufferData(GL_TEXTURE_BUFFER,
                 static_cast<GLsizeiptr>(static_cast<size_t>(tiles) * DT_STATE_STRIDE * sizeof(float)), nullptr,
                 GL_DYNAMIC_DRAW);
  check("allocating the pose buffer");
  layout_ = std::move(layout);
  for (const AtlasPageLayout& l : layout_.pages) {
    AtlasPage page{l, 0, 0, 0};
    const auto make_texture = [&](GLint internal, GLenum format) {
      GLuint t = 0;
      gl_.GenTextures(1, &t);
      gl_.BindTexture(GL_TEXTURE_2D, t);
      gl_.TexImage2D(GL_TEXTURE_2D, 0, internal, l.width, l.height, 0, format, GL_FLOAT, nullptr);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      return t;
    };
    page.color_texture = make_texture(GL_R32F, GL_RED);
    page.depth_texture = make_texture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT);
    gl_.GenFramebuffers(1, &page.framebuffer);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, page.framebuffer);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, page.color_texture, 0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, page.depth_texture, 0);
    pages_.push_back(page);  // owned from here, so a failure below frees it
    const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw BackendError("atlas page " + std::to_string(l.width) + "x" + std::to_string(l.height) +
                         " framebuffer incomplete: " + gl_error_name(status));
    check("allocating an atlas page");
  }
  gl_.BindTexture(GL_TEXTURE_2D, 0);
  tiles_ = tiles;
}

void AtlasRenderer::render(std::span<const Pose> poses) {
  reserve(static_cast<int>(poses.size()));
  states_.assign(poses.size() * DT_STATE_STRIDE, 0.0f);
  for (size_t i = 0; i < poses.size(); ++i) write_pose(poses[i], &states_[i * DT_STATE_STRIDE]);
  upload_states(states_);
  draw();
}

void AtlasRenderer::upload_states(std::span<const float> states) {
  if (states.size() != static_cast<size_t>(tiles_) * DT_STATE_STRIDE)
    throw InputError("atlas renderer: " + std::to_string(states.size()) + " state floats for " +
                     std::to_string(tiles_) + " tiles of " + std::to_string(DT_STATE_STRIDE));
  context_.make_current();
  gl_.BindBuffer(GL_TEXTURE_BUFFER, pose_buffer_);
  gl_.BufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(states.size_bytes()), states.data());
  check("uploading the poses");
}

void AtlasRenderer::draw() {
  if (pages_.empty()) throw InputError("atlas renderer: draw() before reserve()");
  context_.make_current();
  gl_.UseProgram(program_);
  gl_.BindVertexArray(vertex_array_);
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_BUFFER, plane_texture_);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_BUFFER, pose_texture_);
  gl_.Uniform1i(tiles_per_row_location_, layout_.tiles_per_row);
  for (int i = 0; i < 4; ++i) gl_.Enable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i));
  if (cull_back_faces_) {
    // Image row v is window row v (atlas.vert): a triangle wound outward runs clockwise facing the camera.
    gl_.Enable(GL_CULL_FACE);
    gl_.FrontFace(GL_CW);
    gl_.CullFace(GL_BACK);
  } else {
    gl_.Disable(GL_CULL_FACE);
  }
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_TRUE);
  gl_.ClearColor(0, 0, 0, 0);
  gl_.ClearDepth(1.0);
  for (const AtlasPage& page : pages_) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, page.framebuffer);
    const GLenum draw_buffer = GL_COLOR_ATTACHMENT0;
    gl_.DrawBuffers(1, &draw_buffer);
    gl_.Viewport(0, 0, page.layout.width, page.layout.height);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.Uniform1i(first_pose_location_, page.layout.first_tile);
    gl_.Uniform2f(page_size_location_, static_cast<float>(page.layout.width), static_cast<float>(page.layout.height));
    gl_.DrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr, page.layout.tile_count);
  }
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  check("rendering the pose atlas");
}

void AtlasRenderer::read_back(std::span<float> out) {
  const size_t w = static_cast<size_t>(camera_.width), h = static_cast<size_t>(camera_.height);
  if (out.size() != static_cast<size_t>(tiles_) * w * h)
    throw InputError("atlas read-back needs " + std::to_string(static_cast<size_t>(tiles_) * w * h) + " floats, got " +
                     std::to_string(out.size()));
  for (const AtlasPage& page : pages_) {
    const size_t page_width = static_cast<size_t>(page.layout.width);
    staging_.resize(page_width * static_cast<size_t>(page.layout.height));
    read_page(page, staging_);
    // Window row y holds image row y % h of the tiles in page row y / h (no flip: see atlas.vert).
    for (int t = 0; t < page.layout.tile_count; ++t) {
      const size_t x0 = static_cast<size_t>(t % layout_.tiles_per_row) * w;
      const size_t y0 = static_cast<size_t>(t / layout_.tiles_per_row) * h;
      float* tile = out.data() + static_cast<size_t>(page.layout.first_tile + t) * w * h;
      for (size_t v = 0; v < h; ++v) std::copy_n(staging_.data() + (y0 + v) * page_width + x0, w, tile + v * w);
    }
  }
}

void AtlasRenderer::read_page_into(const AtlasPage& page, GLuint pack_buffer, size_t byte_offset) {
  context_.make_current();
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, page.framebuffer);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  // With a pack buffer bound, the pointer argument is a byte offset into it.
  gl_.ReadPixels(0, 0, page.layout.width, page.layout.height, GL_RED, GL_FLOAT,
                 reinterpret_cast<void*>(static_cast<uintptr_t>(byte_offset)));
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check("reading an atlas page into a GL buffer");
}

void AtlasRenderer::finish() {
  context_.make_current();
  gl_.Finish();
}

void AtlasRenderer::read_page(const AtlasPage& page, std::span<float> out) {
  const size_t floats = static_cast<size_t>(page.layout.width) * static_cast<size_t>(page.layout.height);
  if (out.size() != floats)
    throw InputError("atlas page read needs " + std::to_string(floats) + " floats, got " + std::to_string(out.size()));
  context_.make_current();
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, page.framebuffer);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.ReadPixels(0, 0, page.layout.width, page.layout.height, GL_RED, GL_FLOAT, out.data());
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check("reading back an atlas page");
}

}  // namespace depthtrack::render
