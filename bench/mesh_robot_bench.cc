// What collision meshes cost (issue #21): Solo 12 (mesh hulls) against the Unitree A1 (boxes,
// cylinders, spheres; a robot of similar size) on the same low stairs (rise 0.08 m, run 0.25 m).
// Cold each: loading the robot, one whole plan+validate pass (RunPipeline), and one stance check;
// and one hull-vs-stair-box signed distance beside a box-box one. Skips a robot whose files are
// not in ../shared.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <fcl/geometry/shape/box.h>

#include "stairplan/collision/signed_distance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/pipeline/plan_pipeline.h"

namespace {

using namespace stairplan;

std::string SoloUrdf() { return std::string(STAIRPLAN_SHARED_DIR) + "/data/robots/solo12/solo12.urdf"; }
std::string A1Urdf() { return std::string(STAIRPLAN_SHARED_DIR) + "/data/robots/unitree_a1.urdf"; }

MeshSettings SoloMeshes() {
  MeshSettings settings;
  settings.package_path = PackagePath::FromString(std::string(STAIRPLAN_SHARED_DIR) + "/data/robots/solo12");
  settings.use_ros_package_path = false;
  return settings;
}

// A robot loaded once, and what that first load cost: reading the URDF and every mesh file, and
// building its collision model (every hull), which later loads in the process find cached.
struct LoadedRobot {
  std::unique_ptr<RobotModel> model;
  double first_load_ms = 0.0;
};

LoadedRobot LoadFirst(int index) {
  LoadedRobot loaded;
  const std::string path = index == 0 ? SoloUrdf() : A1Urdf();
  if (!std::filesystem::exists(path)) return loaded;
  const auto start = std::chrono::steady_clock::now();
  loaded.model = std::make_unique<RobotModel>(index == 0 ? RobotModel::FromUrdfFile(path, {}, SoloMeshes())
                                                         : RobotModel::FromUrdfFile(path));
  const RobotKinematics kinematics(*loaded.model);
  benchmark::DoNotOptimize(RobotCollisionModel(kinematics).leg_count());
  loaded.first_load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return loaded;
}

// 0: Solo 12, 1: A1; its model null when its file is absent.
const LoadedRobot& Loaded(int index) {
  static const LoadedRobot solo = LoadFirst(0);
  static const LoadedRobot a1 = LoadFirst(1);
  return index == 0 ? solo : a1;
}

const RobotModel* Robot(int index) { return Loaded(index).model.get(); }

Staircase LowStairs() {
  StairSpec spec;
  spec.rise = 0.08;
  spec.run = 0.25;
  return Staircase(spec);
}

void Label(benchmark::State& state, int index) { state.SetLabel(index == 0 ? "solo12 (mesh hulls)" : "a1 (primitives)"); }

// Loading cost: the mesh files are cached per process, so only the first load reads them; the
// hull building is cached per mesh too. What a robot costs after its first load is this; the
// first load's own cost (one sample, wall clock) is the counter first_load_ms.
void BM_LoadRobot(benchmark::State& state) {
  const int index = static_cast<int>(state.range(0));
  if (!Robot(index)) return state.SkipWithError("robot files not found in ../shared");
  const std::string path = index == 0 ? SoloUrdf() : A1Urdf();
  for (auto _ : state) {
    const RobotModel robot = index == 0 ? RobotModel::FromUrdfFile(path, {}, SoloMeshes()) : RobotModel::FromUrdfFile(path);
    const RobotKinematics kinematics(robot);
    benchmark::DoNotOptimize(RobotCollisionModel(kinematics).leg_count());
  }
  Label(state, index);
  state.counters["first_load_ms"] = Loaded(index).first_load_ms;
}

void BM_PlanLowStairs(benchmark::State& state) {
  const int index = static_cast<int>(state.range(0));
  const RobotModel* robot = Robot(index);
  if (!robot) return state.SkipWithError("robot files not found in ../shared");
  const Staircase stairs = LowStairs();
  const PipelineOptions options;
  bool validated = true;
  for (auto _ : state) {
    const PipelineResult result = RunPipeline(*robot, stairs, options);
    validated = validated && result.validated && result.validation.ok;
    benchmark::DoNotOptimize(result.plan);
  }
  Label(state, index);
  state.counters["valid"] = validated ? 1.0 : 0.0;
}

// Standing on the landing in the nominal pose, every contact under its foot.
void BM_StanceCheck(benchmark::State& state) {
  const int index = static_cast<int>(state.range(0));
  const RobotModel* robot = Robot(index);
  if (!robot) return state.SkipWithError("robot files not found in ../shared");
  StanceChecker checker(*robot, LowStairs());
  const NominalStance standing = NominalStanceAt(checker.kinematics(), checker.workspace(), -0.4);
  const BodyPose& body = standing.body;
  const std::array<Eigen::Vector3d, 4>& contacts = standing.contacts_W;
  for (auto _ : state) benchmark::DoNotOptimize(checker.Check(body, contacts).min_clearance);
  Label(state, index);
}

// One signed distance against a 1 m stair box 2 cm below: Solo's shank hull, or a box of its size.
void BM_ShankVsStairBox(benchmark::State& state) {
  const RobotModel* solo = Robot(0);
  if (!solo) return state.SkipWithError("robot files not found in ../shared");
  static const RobotKinematics kinematics(*solo);
  static const RobotCollisionModel model(kinematics);
  const CollisionShape* shank = nullptr;
  for (const CollisionShape& s : model.leg_shapes(0)) {
    if (s.type == ShapeType::kMesh && s.link.find("LOWER") != std::string::npos) shank = &s;
  }
  if (!shank) return state.SkipWithError("no shank mesh");
  const bool as_box = state.range(0) == 1;
  const auto box = MakeFclBox(shank->size);
  const fcl::Boxd stair(0.27, 1.0, 0.08);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity(), stair_pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.04 + 0.5 * shank->size.z() + 0.02);
  for (auto _ : state) {
    benchmark::DoNotOptimize(SignedDistance(as_box ? *box : *shank->geometry, pose, stair, stair_pose).distance);
  }
  state.SetLabel(as_box ? "its bounding box" : "hull, " + std::to_string(shank->mesh->hull_vertices.size()) + " vertices");
}

}  // namespace

BENCHMARK(BM_LoadRobot)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StanceCheck)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShankVsStairBox)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  // Seconds per plan: ctest's smoke run (under the sanitizers too) leaves the plans out.
  if (std::getenv("STAIRPLAN_BENCH_SMOKE") == nullptr) {
    benchmark::RegisterBenchmark("BM_PlanLowStairs", BM_PlanLowStairs)
        ->Arg(0)
        ->Arg(1)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
