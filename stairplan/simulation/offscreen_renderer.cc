#include "stairplan/simulation/offscreen_renderer.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace stairplan {
namespace {

[[noreturn]] void Fail(const std::string& what) {
  throw std::runtime_error("offscreen rendering: " + what + " (EGL error 0x" + [] {
    char hex[16];
    std::snprintf(hex, sizeof hex, "%x", static_cast<unsigned>(eglGetError()));
    return std::string(hex);
  }() + ")");
}

}  // namespace

struct OffscreenRenderer::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  mjvScene scene;
  mjvCamera camera;
  mjvOption option;
  mjrContext gl;
  RenderSettings settings;
  bool scene_made = false, gl_made = false;

  ~Impl() {
    if (gl_made) mjr_freeContext(&gl);
    if (scene_made) mjv_freeScene(&scene);
    if (context != EGL_NO_CONTEXT) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    if (display != EGL_NO_DISPLAY) eglTerminate(display);
  }

  void MakeContext() {
    const char* choice = std::getenv("MUJOCO_GL");
    if (choice != nullptr && std::strcmp(choice, "egl") != 0) {
      throw std::runtime_error(std::string("offscreen rendering: MUJOCO_GL=") + choice +
                               " is not supported by this build; use MUJOCO_GL=egl (or leave it unset)");
    }
    // The surfaceless platform needs no display server and no GPU device.
    const auto get_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_display != nullptr) display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) Fail("no EGL display");
    const EGLint attributes[] = {EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24,
                                 EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, attributes, &config, 1, &count) || count < 1) Fail("no EGL config with OpenGL");
    if (!eglBindAPI(EGL_OPENGL_API)) Fail("EGL cannot bind OpenGL");
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT) Fail("no EGL context");
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) Fail("cannot make the EGL context current");
  }
};

OffscreenRenderer::OffscreenRenderer(const MujocoWorld& world, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  impl_->settings = settings;
  impl_->MakeContext();
  mjv_defaultScene(&impl_->scene);
  mjv_defaultCamera(&impl_->camera);
  mjv_defaultOption(&impl_->option);
  mjr_defaultContext(&impl_->gl);
  mjv_makeScene(world.model(), &impl_->scene, 2000);
  impl_->scene_made = true;
  mjr_makeContext(world.model(), &impl_->gl, mjFONTSCALE_100);
  impl_->gl_made = true;
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->gl);
  if (impl_->gl.currentBuffer != mjFB_OFFSCREEN) throw std::runtime_error("offscreen rendering: MuJoCo has no offscreen buffer");
}

OffscreenRenderer::~OffscreenRenderer() = default;

int OffscreenRenderer::width() const { return impl_->gl.offWidth; }
int OffscreenRenderer::height() const { return impl_->gl.offHeight; }

void OffscreenRenderer::Render(MujocoWorld& world, const Eigen::Vector3d& look_at, std::vector<unsigned char>* rgb) {
  mjvCamera& camera = impl_->camera;
  camera.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) camera.lookat[i] = look_at(i);
  camera.distance = impl_->settings.distance;
  camera.azimuth = impl_->settings.azimuth;
  camera.elevation = impl_->settings.elevation;
  mjv_updateScene(world.model(), world.data(), &impl_->option, nullptr, &camera, mjCAT_ALL, &impl_->scene);
  for (int i = 0; i < impl_->scene.ngeom; ++i) {
    mjvGeom& geom = impl_->scene.geoms[i];
    if (geom.objtype != mjOBJ_GEOM) continue;
    const bool stairs = world.model()->geom_bodyid[geom.objid] == 0;  // the world body holds the stairs
    std::memcpy(geom.rgba, stairs ? impl_->settings.stairs_rgba : impl_->settings.robot_rgba, sizeof geom.rgba);
  }
  const mjrRect viewport = {0, 0, width(), height()};
  mjr_render(viewport, &impl_->scene, &impl_->gl);
  const auto w = static_cast<std::size_t>(width()), h = static_cast<std::size_t>(height());
  std::vector<unsigned char> bottom_up(w * h * 3);
  mjr_readPixels(bottom_up.data(), nullptr, viewport, &impl_->gl);
  rgb->resize(bottom_up.size());
  for (std::size_t row = 0; row < h; ++row) {
    std::memcpy(rgb->data() + row * w * 3, bottom_up.data() + (h - 1 - row) * w * 3, w * 3);
  }
}

}  // namespace stairplan
