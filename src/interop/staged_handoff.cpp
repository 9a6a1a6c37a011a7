// The hand-off that works everywhere: poses go through the host (small: 64 bytes a particle), and
// each atlas page is read by glReadPixels straight into the mapped compute buffer, so the pixels
// are copied once. On PoCL the mapping is the device memory itself.
#include <vector>

#include "interop/atlas_handoff.hpp"

namespace depthtrack::interop {

namespace {
class StagedHandoff final : public AtlasHandoff {
 public:
  StagedHandoff(render::AtlasRenderer& renderer, std::string reason) : renderer_(renderer), reason_(std::move(reason)) {}

  void send_poses(const compute::Buffer<float>& states) override {
    send_poses_through_host(states, renderer_, host_states_);
  }

  void receive_atlas(compute::Buffer<float>& atlas) override {
    const render::AtlasLayout& layout = renderer_.layout();
    for (size_t p = 0; p < renderer_.pages().size(); ++p) {
      const render::AtlasPage& page = renderer_.pages()[p];
      auto mapped = atlas.overwrite(layout.page_offset(p),
                                    static_cast<size_t>(page.layout.width) * static_cast<size_t>(page.layout.height));
      renderer_.read_page(page, mapped.data());
      mapped.publish();
    }
  }

  std::string name() const override { return "staged copy (" + reason_ + ")"; }

 private:
  render::AtlasRenderer& renderer_;
  std::string reason_;
  std::vector<float> host_states_;
};
}  // namespace

void send_poses_through_host(const compute::Buffer<float>& states, render::AtlasRenderer& renderer,
                             std::vector<float>& host) {
  host.resize(states.size());
  states.download(host);
  renderer.upload_states(host);
}

std::unique_ptr<AtlasHandoff> make_staged_handoff(compute::Queue&, render::AtlasRenderer& renderer,
                                                  std::string reason) {
  return std::make_unique<StagedHandoff>(renderer, std::move(reason));
}

}  // namespace depthtrack::interop
