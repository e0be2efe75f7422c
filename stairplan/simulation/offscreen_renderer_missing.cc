// The build found no EGL (libegl-dev): offscreen rendering says so.
#include <stdexcept>

#include "stairplan/simulation/offscreen_renderer.h"

namespace stairplan {

struct OffscreenRenderer::Impl {};

OffscreenRenderer::OffscreenRenderer(const MujocoWorld&, const RenderSettings&) {
  throw std::runtime_error("offscreen rendering: this stairplan was built without EGL (install libegl-dev and rebuild)");
}
OffscreenRenderer::~OffscreenRenderer() = default;
int OffscreenRenderer::width() const { return 0; }
int OffscreenRenderer::height() const { return 0; }
void OffscreenRenderer::Render(MujocoWorld&, const Eigen::Vector3d&, std::vector<unsigned char>*) {}

}  // namespace stairplan
