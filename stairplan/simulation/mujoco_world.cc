#include "stairplan/simulation/mujoco_world.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

namespace stairplan {
namespace {

// MuJoCo prints its warnings on stdout (and into MUJOCO_LOG.TXT in the working folder), where
// `simulate --json` writes its result: they go to stderr.
void WarnOnStderr(const char* message) { std::fprintf(stderr, "MuJoCo warning: %s\n", message); }

// MuJoCo loads from files; a virtual file system keeps the MJCF in memory.
mjModel* LoadFromString(const std::string& mjcf) {
  mju_user_warning = WarnOnStderr;
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "stairplan_world.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf.size())) != 0) {
    throw std::runtime_error("MuJoCo: cannot create the in-memory model file");
  }
  const int index = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[index], mjcf.data(), mjcf.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (model == nullptr) throw std::runtime_error(std::string("MuJoCo rejected the model: ") + error);
  return model;
}

int Require(int id, const std::string& what) {
  if (id < 0) throw std::invalid_argument("MujocoWorld: no " + what);
  return id;
}

bool IsStairGeom(const mjModel* m, int geom) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, geom);
  return name != nullptr && std::strncmp(name, "stair_", 6) == 0;
}

}  // namespace

MujocoWorld::MujocoWorld(const RobotModel& robot, const Staircase& stairs, const MjcfSettings& settings)
    : mjcf_(WriteMjcf(robot, stairs, settings)) {
  model_ = LoadFromString(mjcf_);
  data_ = mj_makeData(model_);
  base_body_ = Require(mj_name2id(model_, mjOBJ_BODY, robot.base_link().c_str()), "base body " + robot.base_link());
  mj_forward(model_, data_);
}

MujocoWorld::~MujocoWorld() {
  if (data_ != nullptr) mj_deleteData(data_);
  if (model_ != nullptr) mj_deleteModel(model_);
}

int MujocoWorld::QposIndex(const std::string& joint) const {
  return model_->jnt_qposadr[Require(mj_name2id(model_, mjOBJ_JOINT, joint.c_str()), "joint " + joint)];
}

int MujocoWorld::QvelIndex(const std::string& joint) const {
  return model_->jnt_dofadr[Require(mj_name2id(model_, mjOBJ_JOINT, joint.c_str()), "joint " + joint)];
}

int MujocoWorld::MotorIndex(const std::string& joint) const {
  return Require(mj_name2id(model_, mjOBJ_ACTUATOR, (joint + "_motor").c_str()), "motor for joint " + joint);
}

void MujocoWorld::SetBasePose(const Eigen::Vector3d& position_W, double yaw, double pitch) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
  // The free joint is the first joint: qpos[0..2] position, qpos[3..6] quaternion (w x y z).
  data_->qpos[0] = position_W.x();
  data_->qpos[1] = position_W.y();
  data_->qpos[2] = position_W.z();
  data_->qpos[3] = q.w();
  data_->qpos[4] = q.x();
  data_->qpos[5] = q.y();
  data_->qpos[6] = q.z();
  for (int i = 0; i < model_->nv; ++i) data_->qvel[i] = 0.0;
  mj_forward(model_, data_);
}

Eigen::Vector3d MujocoWorld::BasePosition() const {
  const double* p = data_->xpos + 3 * base_body_;
  return {p[0], p[1], p[2]};
}

Eigen::Vector3d MujocoWorld::BaseRollPitchYaw() const {
  const double* q = data_->xquat + 4 * base_body_;
  const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
}

void MujocoWorld::Forward() { mj_forward(model_, data_); }
void MujocoWorld::Step() { mj_step(model_, data_); }
double MujocoWorld::time() const { return data_->time; }

std::vector<StairContact> MujocoWorld::StairContacts() const {
  std::vector<StairContact> contacts;
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& c = data_->contact[i];
    const bool first_stair = IsStairGeom(model_, c.geom1);
    const bool second_stair = IsStairGeom(model_, c.geom2);
    if (first_stair == second_stair) continue;
    const int robot_geom = first_stair ? c.geom2 : c.geom1;
    const int stair_geom = first_stair ? c.geom1 : c.geom2;
    StairContact contact;
    contact.body = mj_id2name(model_, mjOBJ_BODY, model_->geom_bodyid[robot_geom]);
    contact.geom = mj_id2name(model_, mjOBJ_GEOM, stair_geom);
    contact.depth = -c.dist;
    contacts.push_back(contact);
  }
  return contacts;
}

double MujocoWorld::RobotMass() const {
  double mass = 0.0;
  for (int b = 1; b < model_->nbody; ++b) mass += model_->body_mass[b];
  return mass;
}

}  // namespace stairplan
