// MuJoCo's own renderer drawing a MujocoWorld offscreen: no window and no display. The OpenGL
// context comes from EGL on Mesa's surfaceless platform (llvmpipe when there is no GPU), chosen as
// MuJoCo's Python bindings choose it: MUJOCO_GL=egl (the default here). Other values are refused
// with a message; OSMesa is not wired (see third_party_notes/mujoco.md).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "stairplan/simulation/mujoco_world.h"

namespace stairplan {

/// The camera and colours of a rendered frame.
struct RenderSettings {
  double distance = 2.2;     ///< camera distance from the base [m]
  double azimuth = 75.0;     ///< [deg], MuJoCo's free camera; 90 looks from the robot's right, along +y
  double elevation = -15.0;  ///< [deg]
  ///@{
  /// Our MJCF gives no colours; the robot and the stairs get these (RGBA) in the picture only.
  float robot_rgba[4] = {0.12f, 0.37f, 0.82f, 1.0f};
  float stairs_rgba[4] = {0.80f, 0.80f, 0.78f, 1.0f};
  ///@}
};

/// One offscreen OpenGL context and MuJoCo scene for one world. Not thread-safe.
class OffscreenRenderer {
 public:
  /// Throws std::runtime_error saying what failed (MUJOCO_GL value, EGL display, config, context).
  explicit OffscreenRenderer(const MujocoWorld& world, const RenderSettings& settings = {});
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Image width [pixels].
  int width() const;
  /// Image height [pixels].
  int height() const;
  /// Renders the world's current state with the camera on `look_at`; `rgb` gets width x height RGB
  /// pixels, rows from the top.
  void Render(MujocoWorld& world, const Eigen::Vector3d& look_at, std::vector<unsigned char>* rgb);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stairplan
