// Collision meshes as FCL shapes: hull clearances against boxes at hand-computed distances, hull
// versus exact-mesh distances within the hull's excess, and Solo 12's collision model standing.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "stairplan/collision/convex_hull.h"
#include "stairplan/collision/mesh_shape.h"
#include "stairplan/collision/robot_collision_model.h"
#include "stairplan/collision/signed_distance.h"
#include "stairplan/collision/stance_check.h"
#include "stairplan/kinematics/mesh_loader.h"
#include "mesh_files.h"
#include "sanitized.h"
#include "shared_solo12.h"
#include "test_paths.h"

using namespace stairplan;
using stairplan::testing::BoxTriangles;
using stairplan::testing::MakeTempDir;
using stairplan::testing::SharedPath;

namespace {

// A stair-like solid: the box [lo, hi] with its FCL geometry at its centre.
struct BoxSolid {
  Box3 box;
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

BoxSolid MakeBoxSolid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  BoxSolid s;
  s.box.min = lo;
  s.box.max = hi;
  s.geometry = MakeFclBox(hi - lo);
  s.pose.translation() = 0.5 * (lo + hi);
  return s;
}

// Distance of `shape` (its geometry placed at `mesh_pose` * centre) to `solid`.
double MeshToSolid(const MeshShape& shape, const Eigen::Isometry3d& mesh_pose, const BoxSolid& solid) {
  SignedDistanceHints hints;
  hints.bounding_radius_a = shape.bounding_radius;
  hints.box_b = &solid.box;
  const Eigen::Isometry3d pose = mesh_pose * Eigen::Translation3d(shape.centre);
  const SignedDistanceResult r = SignedDistance(*shape.geometry, pose, *solid.geometry, solid.pose, hints);
  CHECK_FALSE(r.fallback);
  return r.distance;
}

Eigen::Isometry3d MeshPose(const Eigen::Vector3d& p, const Eigen::Matrix3d& r = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = p;
  return t;
}

std::string SoloMesh(const std::string& name) {
  const std::string folder = SharedPath("data/robots/solo12/example-robot-data/robots/solo_description/meshes/stl/");
  return folder.empty() ? "" : folder + name;
}

}  // namespace

TEST_CASE("a cube mesh's hull is as far from a box as hand geometry says", "[mesh_collision]") {
  const std::string dir = MakeTempDir("mesh-cube");
  stairplan::testing::WriteBytes(dir + "/cube.obj",
                                 stairplan::testing::Obj(BoxTriangles(Eigen::Vector3d::Constant(-0.05), Eigen::Vector3d::Constant(0.05))));
  const auto shape = GetMeshShape(LoadMesh(dir + "/cube.obj", Eigen::Vector3d::Ones()), MeshCollision::kConvexHull);
  CHECK(shape->geometry->getNodeType() == fcl::GEOM_CONVEX);
  CHECK(shape->hull_vertices.size() == 8);
  CHECK(shape->bounding_radius == Approx(0.05 * std::sqrt(3.0)));
  const BoxSolid tread = MakeBoxSolid({-1, -1, -1}, {1, 1, -0.1});  // top at z = -0.1
  const BoxSolid riser = MakeBoxSolid({0.1, -1, -1}, {1, 1, 1});    // face at x = 0.1
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, 0}), tread) == Approx(0.05).margin(1e-9));
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, 0.2}), tread) == Approx(0.25).margin(1e-9));
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, 0}), riser) == Approx(0.05).margin(1e-9));
  // Turned 45 degrees about z, an edge reaches 0.05 sqrt(2) towards the riser.
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, 0}, yaw), riser) == Approx(0.1 - 0.05 * std::sqrt(2.0)).margin(1e-9));
  // Tipped onto an edge over the tread: 0.05 sqrt(2) below its centre.
  const Eigen::Matrix3d roll = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, 0}, roll), tread) == Approx(0.1 - 0.05 * std::sqrt(2.0)).margin(1e-9));
  // Sunk 1 cm into the tread, and 2 cm into the riser.
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, -0.06}), tread) == Approx(-0.01).margin(1e-9));
  CHECK(MeshToSolid(*shape, MeshPose({0.07, 0, 0.5}), riser) == Approx(-0.02).margin(1e-9));
}

TEST_CASE("a mesh that spans no volume has no hull, and the error names its file", "[mesh_collision]") {
  const std::string dir = MakeTempDir("mesh-flat");
  stairplan::testing::WriteBytes(dir + "/flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const auto mesh = LoadMesh(dir + "/flat.obj", Eigen::Vector3d::Ones());
  CHECK_THROWS_WITH(GetMeshShape(mesh, MeshCollision::kConvexHull), Catch::StartsWith(dir + "/flat.obj: the mesh's convex hull has no volume"));
}

TEST_CASE("Solo 12's foot hull sits on a tread at the distances its dimensions give", "[mesh_collision][solo12]") {
  const std::string path = SoloMesh("with_foot/solo_foot.stl");
  if (path.empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  const auto mesh = LoadMesh(path, Eigen::Vector3d::Ones());
  // The foot: a wheel of radius 16 mm in its x-z plane, 16.5 mm thick along y.
  CHECK(mesh->Min().isApprox(Eigen::Vector3d(-0.016, -0.00825, -0.015993), 1e-4));
  CHECK(mesh->Max().isApprox(Eigen::Vector3d(0.016, 0.00825, 0.015993), 1e-4));
  const auto shape = GetMeshShape(mesh, MeshCollision::kConvexHull);
  const BoxSolid tread = MakeBoxSolid({-1, -1, -1}, {1, 1, 0});
  const double bottom = -mesh->Min().z();
  for (const double h : {0.05, 0.02, 0.017}) {
    CHECK(MeshToSolid(*shape, MeshPose({0.1, 0.2, h}), tread) == Approx(h - bottom).margin(1e-7));
    // Rolled onto its side (about x): the half-thickness is below the centre.
    const Eigen::Matrix3d side = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    CHECK(MeshToSolid(*shape, MeshPose({0.1, 0.2, h}, side), tread) == Approx(h - 0.00825).margin(1e-6));
  }
  CHECK(MeshToSolid(*shape, MeshPose({0, 0, bottom - 0.004}), tread) == Approx(-0.004).margin(1e-7));
}

TEST_CASE("Solo 12's hull distances stay within the hull's excess below the exact mesh's", "[mesh_collision][solo12]") {
  if (SoloMesh("").empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const BoxSolid tread = MakeBoxSolid({-1, -1, -1}, {1, 1, 0});
  const BoxSolid riser = MakeBoxSolid({0.3, -1, -1}, {1, 1, 1});
  int closer = 0;
  const int poses = stairplan::testing::FullOrSanitized(60, 8);
  // Under the sanitizers, where building the exact BVH and sampling the hull take most of a
  // minute a link, the lower leg and the foot only (the links that meet the stairs).
  const std::vector<std::string> names{"with_foot/solo_lower_leg_left_side.stl", "with_foot/solo_foot.stl",
                                       "with_foot/solo_upper_leg_left_side.stl"};
  const std::size_t links = stairplan::testing::FullOrSanitized<std::size_t>(names.size(), 2);
  for (std::size_t i = 0; i < links; ++i) {
    const std::string& name = names[i];
    INFO(name);
    const auto mesh = LoadMesh(SoloMesh(name), Eigen::Vector3d::Ones());
    const auto hull = GetMeshShape(mesh, MeshCollision::kConvexHull);
    const auto exact = GetMeshShape(mesh, MeshCollision::kExactMesh);
    CHECK(exact->geometry->getNodeType() == fcl::BV_OBBRSS);
    // Sampling the hull every 4 mm (1 cm under the sanitizers) bounds its excess by the largest
    // sampled distance plus the spacing.
    const double spacing = stairplan::testing::FullOrSanitized(0.004, 0.01);
    const double excess = HullExcess(ComputeConvexHull(mesh->vertices, name), mesh->vertices, mesh->triangles, spacing);
    // A leg link's hull hugs it: no sampled point of the hull is more than 1.5 cm off the mesh.
    CHECK(excess - spacing < 0.015);
    for (int k = 0; k < poses; ++k) {
      const Eigen::Matrix3d r = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
      const Eigen::Vector3d p(0.15 + 0.05 * unit(rng), 0.0, 0.12 + 0.1 * unit(rng));
      // Against stair-sized boxes the nearest point is a hull vertex, so hull and mesh agree; a
      // 1 cm cube near the link can sit in a concavity, where the hull is closer.
      const Eigen::Vector3d cube(p.x() + 0.06 * unit(rng), 0.06 * unit(rng), p.z() + 0.06 * unit(rng));
      const BoxSolid small = MakeBoxSolid(cube - Eigen::Vector3d::Constant(0.005), cube + Eigen::Vector3d::Constant(0.005));
      for (const BoxSolid* solid : {&tread, &riser, &small}) {
        const double d_hull = MeshToSolid(*hull, MeshPose(p, r), *solid);
        const double d_exact = MeshToSolid(*exact, MeshPose(p, r), *solid);
        // Penetration depths are bounds (ours by separating axes, a BVH's per triangle): only
        // distances between separated shapes are compared. GJK on a hull of hundreds of nearly
        // coplanar faces can stop at its iteration limit a few micrometres short (3.6 um seen
        // with clang's build), so the hull's distance is bounded up to that.
        CHECK(d_hull <= d_exact + 1e-5);
        if (d_hull <= 0.0) continue;
        INFO("pose " << k << " hull " << d_hull << " exact " << d_exact << " excess " << excess);
        CHECK(d_exact <= d_hull + excess);
        closer += d_exact - d_hull > 1e-5 ? 1 : 0;
      }
    }
  }
  // The poses do find the hull closer than the mesh somewhere (the bounds are not vacuous).
  CHECK(closer > 0);
}

TEST_CASE("Solo 12's collision model: mesh shapes, mesh feet, a clear stance on the landing", "[mesh_collision][solo12]") {
  const std::string folder = SharedPath("data/robots/solo12");
  if (folder.empty()) {
    WARN("Solo 12 skipped: ../shared not found");
    return;
  }
  for (const MeshCollision mode : {MeshCollision::kConvexHull, MeshCollision::kExactMesh}) {
    INFO(ToString(mode));
    const RobotModel robot = RobotModel::FromUrdfFile(folder + "/solo12.urdf", {}, testing::Solo12Meshes(folder, mode));
    StanceChecker checker(robot, Staircase(StairSpec{}));
    const RobotCollisionModel& model = checker.collision_model();
    REQUIRE(model.body_shapes().size() == 1);
    CHECK(model.body_shapes()[0].type == ShapeType::kMesh);
    for (int l = 0; l < 4; ++l) {
      const auto& shapes = model.leg_shapes(l);
      CHECK(shapes.size() == 4);  // shoulder, upper leg, lower leg, foot
      REQUIRE(model.foot_shape(l) >= 0);
      const CollisionShape& foot = shapes[static_cast<std::size_t>(model.foot_shape(l))];
      CHECK(foot.type == ShapeType::kMesh);
      CHECK(foot.link == robot.legs()[static_cast<std::size_t>(l)].foot_link);
      CHECK(foot.foot_part);
    }
    // Standing on the landing in the nominal pose: every foot's contact point on the landing.
    const NominalStance standing = NominalStanceAt(checker.kinematics(), checker.workspace(), -0.5);
    BodyPose body = standing.body;
    std::array<Eigen::Vector3d, 4> contacts = standing.contacts_W;
    for (int l = 0; l < 4; ++l) {
      CHECK(contacts[static_cast<std::size_t>(l)].z() == Approx(0.0).margin(1e-4));  // front and hind nominal differ by microns
    }
    const StanceResult r = checker.Check(body, contacts);
    CHECK(r.ok());
    // The lowest link above the landing is the shank, whose mesh ends above the foot's rim.
    CHECK(r.min_clearance > 0.0);
    CHECK(r.min_clearance < 0.02);
    CHECK(r.body.distance > 0.1);
    CHECK(r.front_pair.distance > 0.05);
    // Moved forward until LF's contact is 5 mm before the first riser (x = 0): its 16 mm foot
    // wheel is in the riser, while its contact with the landing is still ignored.
    const double shift = -0.005 - contacts[0].x();
    body.position_W.x() += shift;
    for (auto& c : contacts) c.x() += shift;
    const StanceResult against = checker.Check(body, contacts);
    CHECK(against.status == StanceStatus::kCollision);
    CHECK(against.worst_leg <= 1);  // a front leg: both front feet stand as far forward
    CHECK(against.legs[0].stairs.part == StairPart::kRiser);
    CHECK(against.legs[0].stairs.distance < -0.005);
  }
}
