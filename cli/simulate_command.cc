// `stairplan simulate plan.json`: execute a plan in MuJoCo on the stairs it names (or on others,
// --stairs, as `robustness` does) and print a
// summary of the physics outcome, or with --json the outcome as JSON (exit 0 when the robot got
// there cleanly, 3 when it did not).
#include <csignal>
#include <cstdio>
#include <memory>
#include <iostream>
#include <sstream>

#include "stairplan/geometry/stair_friction.h"
#include "cli/cli_common.h"
#include "cli/stair_flags.h"
#include "stairplan/planning/json_version.h"
#include "stairplan/planning/plan_json_reader.h"
#include "stairplan/simulation/plan_executor.h"
#include "stairplan/simulation/offscreen_renderer.h"
#include "stairplan/simulation/video_encoder.h"
#include "stairplan/simulation/sim_outcome_json.h"

namespace stairplan::cli {
namespace {

// The base against the plan over time, one row per recorded frame.
std::string TraceCsv(const SimulationOutcome& outcome) {
  std::ostringstream csv;
  csv << "t,x,y,z,roll,pitch,yaw,plan_x,plan_y,plan_z,plan_pitch,stance\n";
  for (const SimFrame& f : outcome.frames) {
    csv << f.t << "," << f.base_W.x() << "," << f.base_W.y() << "," << f.base_W.z() << "," << f.base_rpy.x() << ","
        << f.base_rpy.y() << "," << f.base_rpy.z() << "," << f.planned_W.x() << "," << f.planned_W.y() << ","
        << f.planned_W.z() << "," << f.planned_pitch << ",";
    for (bool s : f.stance) csv << (s ? 'S' : '-');
    csv << "\n";
  }
  return csv.str();
}

// The run drawn by MuJoCo's renderer into an mp4 and/or PNG frames; the renderer and the encoders
// start at the first frame, when the world exists.
class Renderings {
 public:
  Renderings(std::string video, std::string frames_dir, double fps)
      : video_(std::move(video)), frames_dir_(std::move(frames_dir)), fps_(fps) {}

  void Add(MujocoWorld& world) {
    if (!renderer_) {
      renderer_ = std::make_unique<OffscreenRenderer>(world);
      std::signal(SIGPIPE, SIG_IGN);  // a failing ffmpeg is reported by Write, not by a signal
      if (!video_.empty()) {
        encoders_.push_back(std::make_unique<VideoEncoder>(VideoOutput::kMp4, video_, renderer_->width(), renderer_->height(), fps_));
      }
      if (!frames_dir_.empty()) {
        encoders_.push_back(std::make_unique<VideoEncoder>(VideoOutput::kPngFrames, frames_dir_, renderer_->width(),
                                                           renderer_->height(), fps_));
      }
    }
    const Eigen::Vector3d base = world.BasePosition();
    renderer_->Render(world, base - Eigen::Vector3d(0.0, 0.0, 0.15), &rgb_);
    for (auto& encoder : encoders_) encoder->Write(rgb_);
    ++frames_;
  }
  void Finish() {
    for (auto& encoder : encoders_) encoder->Finish();
  }
  int frames() const { return frames_; }

 private:
  std::string video_, frames_dir_;
  double fps_;
  std::unique_ptr<OffscreenRenderer> renderer_;
  std::vector<std::unique_ptr<VideoEncoder>> encoders_;
  std::vector<unsigned char> rgb_;
  int frames_ = 0;
};

int RunSimulate(const std::vector<std::string>& args) {
  CLI::App app("Execute a plan in MuJoCo and report what happened", "simulate");
  std::string path, robot_path, frames_dir, video, out, trace;
  std::vector<std::string> overrides;
  StairFlags true_stairs;
  double frame_ms = 100.0, friction = kStairFriction, video_speed = 1.0;
  bool print_json = false, no_responses = false;
  std::string impacts = "torque_residual", stance_forces = "gait";
  app.add_option("plan", path, "plan.json written by `stairplan plan`")->required();
  app.add_option("--robot", robot_path, "Robot URDF (default: the one the plan names)");
  app.add_option("--stairs", true_stairs.file, "Stairs YAML to execute on instead of the plan's own (stairs that differ from the model)");
  RobotFlags robot_flags;
  AddRobotFlags(app, robot_flags);
  app.add_option("--video", video, "Render the run with MuJoCo's renderer offscreen (EGL) into this mp4 (ffmpeg)");
  app.add_option("--frames", frames_dir, "Render the run into this directory as PNGs, one every --frame-ms");
  app.add_option("--video-speed", video_speed, "Playback speed of --video against the plan's clock (default 1)")
      ->check(CLI::Range(0.01, 100.0));
  const CLI::Option* frame_option =
      app.add_option("--frame-ms", frame_ms,
                     "Interval between frames [ms] (default 100, 40 with --video or --frames); given, --out also holds "
                     "the frames (for `stairplan view --sim`)")
          ->check(CLI::Range(1.0, 10000.0));
  std::ostringstream friction_help;
  friction_help << "Sliding friction of every contact (default " << kStairFriction << ")";
  app.add_option("--friction", friction, friction_help.str())->check(CLI::Range(0.0, 10.0));
  app.add_option("--out", out, "Also write the JSON result to this file");
  app.add_option("--set", overrides,
                 "Override a simulation setting, name=value (e.g. kp_per_kg=10; time_scale=3 replays 3x slower than planned)");
  app.add_option("--trace", trace, "Write a CSV of the base (measured and planned) every --frame-ms");
  app.add_option("--impacts", impacts,
                 "How impacts are detected: torque_residual (joint torques against the model, default), contacts "
                 "(MuJoCo's contact list) or none")
      ->check(CLI::IsMember({"torque_residual", "contacts", "none"}));
  app.add_option("--stance-forces", stance_forces,
                 "Where the stance feet's forces come from: gait (default: the convex MPC for the trot, the wrench for "
                 "the crawls and the walk), wrench (the planned body's PD wrench distributed each step) or mpc (the "
                 "convex MPC over the plan's next 0.4 s)")
      ->check(CLI::IsMember({"gait", "wrench", "mpc"}));
  app.add_flag("--no-responses", no_responses, "Detect and record impacts but do not answer them");
  app.add_flag("--json", print_json, "Print the outcome as JSON (the --out file's contents) instead of the summary");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("simulate", [&] {
    const PlanFile file = ReadPlanJsonFile(path);
    const RobotModel robot = LoadPlanRobot(file, robot_path, robot_flags);
    const Staircase stairs = true_stairs.file.empty() ? Staircase(file.stairs) : ResolveStairs(true_stairs);
    if (!frames_dir.empty()) MakeOutputDir(frames_dir, "--frames");
    const bool rendering = !video.empty() || !frames_dir.empty();
    if (rendering && frame_option->count() == 0) frame_ms = 40.0;
    SimSettings settings;
    settings.world.friction = friction;
    settings.impact.source = impacts == "none" ? ImpactSource::kNone
                             : impacts == "contacts" ? ImpactSource::kContacts
                                                     : ImpactSource::kTorqueResidual;
    settings.impact.respond = !no_responses;
    settings.stance_forces = ParseStanceForceSource(stance_forces);
    const bool record = rendering || !trace.empty() || frame_option->count() > 0;
    settings.frame_interval = record ? frame_ms / 1000.0 : 0.0;
    for (const std::string& o : overrides) {
      const std::size_t eq = o.find('=');
      double value = 0.0;
      try {
        value = std::stod(o.substr(eq == std::string::npos ? o.size() : eq + 1));
      } catch (const std::exception&) {
        throw BadInput("--set: expected name=value (got '" + o + "')");
      }
      try {
        settings.Set(o.substr(0, eq), value);
        settings.Validate();
      } catch (const std::invalid_argument& e) {
        throw BadInput(std::string("--set: ") + e.what());
      }
    }
    Plan plan = file.plan;
    plan.facing = file.facing;
    Renderings renderings(video, frames_dir, video_speed / settings.frame_interval);
    const SimulationOutcome outcome =
        rendering ? Simulate(robot, stairs, plan, settings, [&](MujocoWorld& world, double) { renderings.Add(world); })
                  : Simulate(robot, stairs, plan, settings);
    renderings.Finish();
    nlohmann::json json = SimulationToJson(outcome);
    json["plan"] = path;
    json["robot"] = robot.name();
    if (!trace.empty()) WriteFileAtomically(trace, TraceCsv(outcome));
    if (rendering) {
      json["video"] = {{"file", video}, {"frames_dir", frames_dir}, {"frames", renderings.frames()},
                       {"fps", video_speed / settings.frame_interval},
                       {"duration_s", renderings.frames() * settings.frame_interval / video_speed}};
    }
    const std::string text = StampVersion(json).dump(2) + "\n";
    if (!out.empty() && frame_option->count() > 0) {
      nlohmann::json with_frames = StampVersion(json);
      with_frames["frames"] = SimFramesToJson(outcome.frames);
      WriteFileAtomically(out, with_frames.dump() + "\n");
    } else if (!out.empty()) {
      WriteFileAtomically(out, text);
    }
    if (print_json) {
      std::cout << text;
    } else {
      std::cout << "stairplan simulate: " << path << ": " << ToString(outcome.status)
                << (outcome.Passed() ? "" : " (" + outcome.FirstCause() + ")") << "; " << outcome.landings.size()
                << " landings, max error " << outcome.MaxLandingError() * 1000 << " mm; peak torque "
                << outcome.max_torque_ratio * 100 << "% of the limit; time_scale " << outcome.time_scale
                << ", plan ZMP margin " << outcome.plan_zmp_margin_m * 1000 << " mm; stance forces "
                << ToString(outcome.stance_forces) << "; real-time factor "
                << outcome.real_time_factor << "\n";
      for (const ImpactRecord& e : outcome.impacts) {
        if (e.kind == ImpactKind::kTouchdown || e.kind == ImpactKind::kLiftoffScuff) continue;  // the routine ones
        std::cout << "  impact t=" << e.t << " s  " << e.leg << "  " << ToString(e.kind) << " -> " << ToString(e.response)
                  << " (" << ToString(e.source) << ")\n";
      }
      if (!out.empty()) std::cout << "  wrote: " << out << "\n";
    }
    return outcome.Passed() ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kSimulateRegistrar({"simulate", "execute a plan.json in MuJoCo (exit 3 when the robot fails)", RunSimulate});

}  // namespace
}  // namespace stairplan::cli
