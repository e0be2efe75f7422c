#include "stairplan/kinematics/leg_kinematics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>

namespace stairplan {
namespace {

constexpr int kDof = 3;
// Joint ranges wider than a turn (ANYmal's placeholder +/-3 pi) are sampled over one turn only.
constexpr double kSampleRange = M_PI;

Eigen::Isometry3d ToEigen(const KDL::Frame& f) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = f.M(r, c);
    t.translation()(r) = f.p(r);
  }
  return t;
}

Eigen::Vector3d ToEigen(const KDL::Vector& v) { return {v.x(), v.y(), v.z()}; }

// How far outside the sampled reach a target must be to be called unreachable untried.
constexpr double kReachSlack = 0.01;     // relative
constexpr double kReachSlackAbs = 1e-3;  // [m]

double SampleLo(double lo) { return std::max(lo, -kSampleRange); }
double SampleHi(double hi) { return std::min(hi, kSampleRange); }

}  // namespace

LegKinematics::LegKinematics(const LegModel& leg, const KDL::Tree& tree, const std::string& base_link) : leg_(leg) {
  auto chain = std::make_shared<KDL::Chain>();
  if (!tree.getChain(base_link, leg.foot_link, *chain)) {
    throw std::invalid_argument("LegKinematics: leg " + leg.name + ": no KDL chain from '" + base_link + "' to '" +
                                leg.foot_link + "'");
  }
  if (chain->getNrOfJoints() != kDof || leg.limits.size() != kDof) {
    throw std::invalid_argument("LegKinematics: leg " + leg.name + " (foot '" + leg.foot_link + "') has " +
                                std::to_string(chain->getNrOfJoints()) + " movable joints; 3 are supported");
  }
  chain_ = chain;
  int joint = 0;
  for (unsigned i = 0; i < chain_->getNrOfSegments(); ++i) {
    const KDL::Segment& segment = chain_->getSegment(i);
    segment_links_.push_back(segment.getName());
    if (segment.getJoint().getType() != KDL::Joint::None) {
      knee_segment_ = static_cast<int>(i);
      joint_segment_[static_cast<std::size_t>(joint++)] = static_cast<int>(i);
    }
  }
  for (int j = 0; j < kDof; ++j) {
    lower_(j) = leg.limits[static_cast<std::size_t>(j)].lower;
    upper_(j) = leg.limits[static_cast<std::size_t>(j)].upper;
    if (!(lower_(j) <= upper_(j))) {
      throw std::invalid_argument("LegKinematics: leg " + leg.name + ": joint '" + leg.joint_names[static_cast<std::size_t>(j)] +
                                  "' has lower limit above upper limit");
    }
  }
  hip_B_ = leg.hip_B;
  LegWorkspace ws(*this);
  BuildFkSegments(ws);
  BuildKneeTable(ws);
  ComputeReach(ws);
  ComputeNominal(ws);
}

bool LegKinematics::WithinLimits(const Eigen::Vector3d& q, double tol) const {
  return ((q.array() >= lower_.array() - tol) && (q.array() <= upper_.array() + tol)).all();
}

Eigen::Vector3d LegKinematics::Clamp(const Eigen::Vector3d& q) const { return q.cwiseMax(lower_).cwiseMin(upper_); }

Eigen::Isometry3d LegKinematics::FootPose(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  return ToEigen(ws.frames_.back());
}

Eigen::Vector3d LegKinematics::FootPosition(const Eigen::Vector3d& q, LegWorkspace& ws) const { return SegmentFrames(q, ws); }

Eigen::Vector3d LegKinematics::KneePosition(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  return ToEigen(ws.frames_[static_cast<std::size_t>(knee_segment_)].p);
}

const std::vector<Eigen::Isometry3d>& LegKinematics::LinkFrames(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  if (!ws.frames_B_current_) {
    for (std::size_t i = 0; i < ws.frames_.size(); ++i) ws.frames_B_[i] = ToEigen(ws.frames_[i]);
    ws.frames_B_current_ = true;
  }
  return ws.frames_B_;
}

Eigen::Isometry3d LegKinematics::LinkFrame(const Eigen::Vector3d& q, int i, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  return ToEigen(ws.frames_.at(static_cast<std::size_t>(i)));
}

Eigen::Matrix3d LegKinematics::FootJacobian(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  return JacobianFromFrames(ws);
}

void LegKinematics::BuildFkSegments(LegWorkspace& ws) {
  fk_segments_.clear();
  std::vector<FkSegment> segments;
  for (unsigned i = 0; i < chain_->getNrOfSegments(); ++i) {
    const KDL::Segment& segment = chain_->getSegment(i);
    const KDL::Joint& joint = segment.getJoint();
    FkSegment s;
    const Eigen::Isometry3d at_zero = ToEigen(segment.pose(0.0));
    s.rotation = at_zero.linear();
    s.translation = at_zero.translation();
    if (joint.getType() == KDL::Joint::RotAxis) {
      s.revolute = true;
      s.axis = ToEigen(joint.JointAxis()).normalized();
      s.origin = ToEigen(joint.JointOrigin());
    } else if (joint.getType() != KDL::Joint::None) {
      return;  // KDL's solver for other joint types
    }
    segments.push_back(s);
  }
  // A segment turns about its joint's line: pose(q) = (R M0, o + R (p0 - o)) with (M0, p0) its
  // pose at q = 0 and R the turn by q about the axis through o. KDL's joints may carry a scale or
  // offset this leaves out: the frames must agree with KDL's solver over the joints' ranges.
  fk_segments_ = std::move(segments);
  if (!FkSegmentsAgreeWithKdl(ws)) fk_segments_.clear();
  ws.frames_current_ = false;
}

bool LegKinematics::FkSegmentsAgreeWithKdl(LegWorkspace& ws) const {
  // Three levels per joint across its range (27 configurations), shifted so that no joint sits
  // at its zero, where a wrong axis sign would go unseen.
  for (int k = 0; k < 27; ++k) {
    Eigen::Vector3d q;
    for (int j = 0; j < kDof; ++j) {
      const int level = (k / (j == 0 ? 1 : j == 1 ? 3 : 9)) % 3;
      q(j) = SampleLo(lower_(j)) + 0.5 * level * (SampleHi(upper_(j)) - SampleLo(lower_(j))) + 0.1 * (j + 1);
      ws.q_(static_cast<unsigned>(j)) = q(j);
    }
    ws.fk_->JntToCart(ws.q_, ws.frames_);
    const std::vector<KDL::Frame> kdl = ws.frames_;
    ws.frames_current_ = false;
    SegmentFrames(q, ws);
    for (std::size_t i = 0; i < kdl.size(); ++i) {
      for (int r = 0; r < 3; ++r) {
        bool agree = std::abs(kdl[i].p(r) - ws.frames_[i].p(r)) <= 1e-12;
        for (int c = 0; c < 3; ++c) agree = agree && std::abs(kdl[i].M(r, c) - ws.frames_[i].M(r, c)) <= 1e-12;
        if (!agree) return false;
      }
    }
  }
  return true;
}

Eigen::Vector3d LegKinematics::SegmentFrames(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  // The planners ask for several things at one q in a row (foot, Jacobian, flexion joint, link
  // frames): the chain is run once per q. A NaN q never equals the kept one, so it is recomputed.
  if (!ws.frames_current_ || !(ws.frames_q_.array() == q.array()).all()) {
    if (fk_segments_.empty()) {
      for (int j = 0; j < kDof; ++j) ws.q_(static_cast<unsigned>(j)) = q(j);
      ws.fk_->JntToCart(ws.q_, ws.frames_);
    } else {
      Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      int j = 0;
      for (std::size_t i = 0; i < fk_segments_.size(); ++i) {
        const FkSegment& s = fk_segments_[i];
        if (s.revolute) {
          // Rodrigues' turn by q(j) about the unit axis a: c I + s [a]x + (1 - c) a a'.
          const double angle = q(j++), c = std::cos(angle), sn = std::sin(angle), v = 1.0 - c;
          const Eigen::Vector3d& a = s.axis;
          Eigen::Matrix3d r;
          r << c + v * a.x() * a.x(), v * a.x() * a.y() - sn * a.z(), v * a.x() * a.z() + sn * a.y(),
              v * a.x() * a.y() + sn * a.z(), c + v * a.y() * a.y(), v * a.y() * a.z() - sn * a.x(),
              v * a.x() * a.z() - sn * a.y(), v * a.y() * a.z() + sn * a.x(), c + v * a.z() * a.z();
          p.noalias() += m * (s.origin + r * (s.translation - s.origin));
          m = m * (r * s.rotation).eval();
        } else {
          p.noalias() += m * s.translation;
          m = m * s.rotation;
        }
        KDL::Frame& f = ws.frames_[i];
        for (int row = 0; row < 3; ++row) {
          for (int col = 0; col < 3; ++col) f.M(row, col) = m(row, col);
          f.p(row) = p(row);
        }
      }
    }
    ws.frames_q_ = q;
    ws.frames_current_ = true;
    ws.frames_B_current_ = false;
  }
  return ToEigen(ws.frames_.back().p);
}

LegKinematics::JointLine LegKinematics::JointLineFromFrames(const LegWorkspace& ws, int j) const {
  const auto segment = static_cast<std::size_t>(joint_segment_[static_cast<std::size_t>(j)]);
  const KDL::Joint& joint = chain_->getSegment(static_cast<unsigned>(segment)).getJoint();
  // A joint's origin and axis are given in its segment's base frame, the tip of the segment before.
  const KDL::Frame base = segment == 0 ? KDL::Frame::Identity() : ws.frames_[segment - 1];
  JointLine line;
  line.origin = ToEigen(base * joint.JointOrigin());
  line.axis = ToEigen(base.M * joint.JointAxis());
  line.prismatic = joint.getType() >= KDL::Joint::TransAxis && joint.getType() <= KDL::Joint::TransZ;
  return line;
}

LegKinematics::JointLine LegKinematics::JointLineAt(const Eigen::Vector3d& q, int j, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  JointLine line = JointLineFromFrames(ws, j);
  line.axis.normalize();
  return line;
}

Eigen::Matrix3d LegKinematics::JacobianFromFrames(const LegWorkspace& ws) const {
  const Eigen::Vector3d foot = ToEigen(ws.frames_.back().p);
  Eigen::Matrix3d J;
  for (int j = 0; j < kDof; ++j) {
    const JointLine line = JointLineFromFrames(ws, j);
    J.col(j) = line.prismatic ? line.axis : line.axis.cross(foot - line.origin);
  }
  return J;
}

double LegKinematics::Descend(const Eigen::Vector3d& target, Eigen::Vector3d& q, bool clamp, const IkSettings& settings,
                              LegWorkspace& ws, int& iterations) const {
  // Every evaluation leaves its segment frames in `ws`: an accepted step's Jacobian is built from
  // them, without a second pass through the chain.
  Eigen::Vector3d error = target - SegmentFrames(q, ws);
  double norm = error.norm();
  double lambda = 1e-6;
  bool need_jacobian = true;
  Eigen::Matrix3d J;
  for (int it = 0; it < settings.max_iterations && norm > settings.tolerance; ++it) {
    ++iterations;
    if (need_jacobian) J = JacobianFromFrames(ws);
    // Joints resting on a limit that the unconstrained step would push further out are frozen
    // for this step (an active set), so the others still make full Gauss-Newton progress instead
    // of the whole step being clipped.
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    Eigen::Matrix<bool, 3, 1> frozen = Eigen::Matrix<bool, 3, 1>::Constant(false);
    for (int pass = 0; pass < 2; ++pass) {
      Eigen::Matrix3d Jf = J;
      for (int j = 0; j < kDof; ++j) {
        if (frozen(j)) Jf.col(j).setZero();
      }
      Eigen::Matrix3d normal = Jf.transpose() * Jf;
      // Marquardt's scaling keeps the damping meaningful for joints of very different leverage.
      normal.diagonal() += lambda * (Eigen::Vector3d::Ones() + normal.diagonal());
      step = normal.inverse() * (Jf.transpose() * error);
      if (!clamp) break;
      bool changed = false;
      for (int j = 0; j < kDof; ++j) {
        const bool out = (q(j) <= lower_(j) && step(j) < 0.0) || (q(j) >= upper_(j) && step(j) > 0.0);
        if (out && !frozen(j)) {
          frozen(j) = true;
          changed = true;
        }
      }
      if (!changed) break;
    }
    for (int j = 0; j < kDof; ++j) {
      if (frozen(j)) step(j) = 0.0;
    }
    const double step_norm = step.norm();
    if (!std::isfinite(step_norm) || step_norm < 1e-15) break;
    if (step_norm > settings.max_step) step *= settings.max_step / step_norm;
    Eigen::Vector3d trial = q + step;
    if (clamp) trial = Clamp(trial);
    const Eigen::Vector3d trial_error = target - SegmentFrames(trial, ws);
    const double trial_norm = trial_error.norm();
    if (trial_norm < norm) {
      q = trial;
      error = trial_error;
      norm = trial_norm;
      lambda = std::max(lambda * 0.1, 1e-9);
      need_jacobian = true;
    } else {
      lambda *= 100.0;
      need_jacobian = false;  // same q, same Jacobian
      if (lambda > 1e4) break;  // stalled: against a limit or at the edge of the workspace
    }
  }
  return norm;
}

Eigen::Vector3d LegKinematics::RestartSeed(int k) const {
  Eigen::Vector3d q;
  for (int j = 0; j < kDof; ++j) {
    const double lo = SampleLo(lower_(j)), hi = SampleHi(upper_(j));
    const double fraction = ((k >> j) & 1) ? 0.8 : 0.2;
    q(j) = lo + fraction * (hi - lo);
  }
  return q;
}

bool LegKinematics::BeyondLimitedReach(const Eigen::Vector3d& foot_B) const {
  // reach_ is sampled, so its ends are a little inside the true ones: only a target clearly
  // outside them is beyond every configuration within the limits.
  const double d = (foot_B - hip_B_).norm();
  return d > reach_.hi * (1.0 + kReachSlack) + kReachSlackAbs || d < reach_.lo * (1.0 - kReachSlack) - kReachSlackAbs;
}

IkResult LegKinematics::SolveFootIk(const Eigen::Vector3d& foot_B, LegWorkspace& ws, const IkSettings& settings) const {
  return SolveFootIk(foot_B, nominal_, ws, settings);
}

IkResult LegKinematics::SolveFootIk(const Eigen::Vector3d& foot_B, const Eigen::Vector3d& seed, LegWorkspace& ws,
                                    const IkSettings& settings) const {
  if (!foot_B.allFinite()) throw std::invalid_argument("LegKinematics::SolveFootIk: leg " + leg_.name + ": foot_B is not finite");
  if (!seed.allFinite()) throw std::invalid_argument("LegKinematics::SolveFootIk: leg " + leg_.name + ": seed is not finite");
  settings.Validate();
  IkResult result;
  result.q = AimedSeed(foot_B, Clamp(seed), ws);
  result.error = Descend(foot_B, result.q, true, settings, ws, result.iterations);
  if (result.error <= settings.tolerance) {
    result.status = IkStatus::kSolved;
    return result;
  }
  // The planners probe many unreachable targets: farther than the links laid end to end is out of
  // reach for any joint angles, and beyond the reach within the limits no restart can help.
  if ((foot_B - hip_B_).norm() > leg_.max_reach + 1e-9) return result;  // kOutOfReach
  const int restarts = BeyondLimitedReach(foot_B) ? 0 : settings.max_restarts;
  // A descent that stalls against a joint limit often has a solution on another branch: restart
  // from spread-out seeds before giving up.
  for (int k = 0; k < restarts && result.error > settings.tolerance; ++k) {
    Eigen::Vector3d q = RestartSeed(k);
    const double error = Descend(foot_B, q, true, settings, ws, result.iterations);
    if (error < result.error) {
      result.q = q;
      result.error = error;
    }
  }
  if (result.error <= settings.tolerance) {
    result.status = IkStatus::kSolved;
    return result;
  }
  // Tell "beyond the leg" from "only beyond the limits" by solving again without the limits.
  Eigen::Vector3d free_q = result.q;
  int unused = 0;
  const double free_error = Descend(foot_B, free_q, false, settings, ws, unused);
  result.status = free_error <= std::max(settings.tolerance, 1e-7) ? IkStatus::kJointLimits : IkStatus::kOutOfReach;
  return result;
}

void LegKinematics::BuildKneeTable(LegWorkspace& ws) {
  const double lo = SampleLo(lower_(2)), hi = SampleHi(upper_(2));
  for (int i = 0; i < kKneeTable; ++i) {
    const Eigen::Vector3d q(0.0, 0.0, lo + (hi - lo) * i / (kKneeTable - 1));
    const std::vector<Eigen::Isometry3d>& frames = LinkFrames(q, ws);
    knee_q_[static_cast<std::size_t>(i)] = q(2);
    knee_distance_[static_cast<std::size_t>(i)] =
        (frames.back().translation() - frames[static_cast<std::size_t>(joint_segment_[1])].translation()).norm();
  }
  extension_.lo = *std::min_element(knee_distance_.begin(), knee_distance_.end());
  extension_.hi = *std::max_element(knee_distance_.begin(), knee_distance_.end());
}

Eigen::Vector3d LegKinematics::FlexionPosition(const Eigen::Vector3d& q, LegWorkspace& ws) const {
  SegmentFrames(q, ws);
  return ToEigen(ws.frames_[static_cast<std::size_t>(joint_segment_[1])].p);
}

Eigen::Vector3d LegKinematics::AimedSeed(const Eigen::Vector3d& target, const Eigen::Vector3d& seed, LegWorkspace& ws) const {
  Eigen::Vector3d q = seed;
  // Knee: the flexion joint's origin does not move with flexion or knee, and for the usual leg
  // (parallel flexion and knee axes) the foot's distance from it depends on the knee alone.
  {
    SegmentFrames(q, ws);
    const double want = (target - ToEigen(ws.frames_[static_cast<std::size_t>(joint_segment_[1])].p)).norm();
    double best = q(2), best_gap = std::numeric_limits<double>::infinity();
    for (int i = 0; i + 1 < kKneeTable; ++i) {
      const double d0 = knee_distance_[static_cast<std::size_t>(i)] - want;
      const double d1 = knee_distance_[static_cast<std::size_t>(i + 1)] - want;
      if (d0 * d1 > 0.0 || d0 == d1) continue;
      const double a = d0 / (d0 - d1);
      const double knee = knee_q_[static_cast<std::size_t>(i)] + a * (knee_q_[static_cast<std::size_t>(i + 1)] - knee_q_[static_cast<std::size_t>(i)]);
      if (std::abs(knee - seed(2)) < best_gap) {
        best_gap = std::abs(knee - seed(2));
        best = knee;
      }
    }
    q(2) = best;
  }
  // Flexion then abduction, twice: turn each about its axis to point the foot at the target.
  for (int sweep = 0; sweep < 2; ++sweep) {
    for (int j : {1, 0}) {
      const Eigen::Vector3d foot = SegmentFrames(q, ws);
      const JointLine line = JointLineFromFrames(ws, j);
      const Eigen::Vector3d& origin = line.origin;
      const Eigen::Vector3d axis = line.axis.normalized();
      Eigen::Vector3d u = foot - origin, v = target - origin;
      u -= u.dot(axis) * axis;
      v -= v.dot(axis) * axis;
      if (u.norm() < 1e-9 || v.norm() < 1e-9) continue;
      q(j) += std::atan2(axis.dot(u.cross(v)), u.dot(v));
      // The same direction a turn away may be within limits (Unitree thighs span 5.2 rad).
      for (const double turn : {2.0 * M_PI, -2.0 * M_PI}) {
        if ((q(j) < lower_(j) || q(j) > upper_(j)) && q(j) + turn >= lower_(j) && q(j) + turn <= upper_(j)) q(j) += turn;
      }
    }
    q = Clamp(q);
  }
  return q;
}

void LegKinematics::ComputeReach(LegWorkspace& ws) {
  constexpr int kSamples = 15;
  reach_.lo = std::numeric_limits<double>::infinity();
  reach_.hi = 0.0;
  Eigen::Vector3d q;
  for (int a = 0; a < kSamples; ++a) {
    for (int b = 0; b < kSamples; ++b) {
      for (int c = 0; c < kSamples; ++c) {
        const int index[3] = {a, b, c};
        for (int j = 0; j < kDof; ++j) {
          const double lo = SampleLo(lower_(j)), hi = SampleHi(upper_(j));
          q(j) = lo + (hi - lo) * index[j] / (kSamples - 1);
        }
        const double d = (FootPosition(q, ws) - hip_B_).norm();
        reach_.lo = std::min(reach_.lo, d);
        reach_.hi = std::max(reach_.hi, d);
      }
    }
  }
}

void LegKinematics::ComputeNominal(LegWorkspace& ws) {
  // Target: the foot under the hip at 3/4 of the reach, as a standing robot has it.
  const Eigen::Vector3d target(hip_B_.x(), leg_.foot_zero_B.y(), hip_B_.z() - 0.75 * reach_.hi);
  const double inward = hip_B_.x() >= 0.0 ? -1.0 : 1.0;  // direction of the body centre along x
  // Abduction stays near zero (ANYmal B's +/-3 pi limits would otherwise allow a leg folded over
  // itself); flexion and knee are searched over their whole (one-turn) range.
  double haa_lo = std::max(lower_(0), -0.5), haa_hi = std::min(upper_(0), 0.5);
  if (haa_lo > haa_hi) {
    haa_lo = SampleLo(lower_(0));
    haa_hi = SampleHi(upper_(0));
  }
  constexpr int kAbduction = 5, kSamples = 25;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector3d q, best = Clamp(Eigen::Vector3d::Zero());
  for (int a = 0; a < kAbduction; ++a) {
    q(0) = haa_lo + (haa_hi - haa_lo) * a / (kAbduction - 1);
    for (int b = 0; b < kSamples; ++b) {
      q(1) = SampleLo(lower_(1)) + (SampleHi(upper_(1)) - SampleLo(lower_(1))) * b / (kSamples - 1);
      for (int c = 0; c < kSamples; ++c) {
        q(2) = SampleLo(lower_(2)) + (SampleHi(upper_(2)) - SampleLo(lower_(2))) * c / (kSamples - 1);
        const Eigen::Vector3d foot = FootPosition(q, ws);
        const Eigen::Vector3d knee = KneePosition(q, ws);
        // The knee should point to the body centre: ahead of the hip-foot line for hind legs,
        // behind it for front legs. A wrong bend costs as much as 5 cm of foot error; a small
        // pull towards the URDF's zero pose breaks ties between equivalent folded poses.
        const double bend = (knee.x() - 0.5 * (hip_B_.x() + foot.x())) * inward;
        const double cost = (foot - target).norm() + (bend > 0.01 ? 0.0 : 0.05) + 0.005 * q.norm();
        if (cost < best_cost) {
          best_cost = cost;
          best = q;
        }
      }
    }
  }
  IkSettings settings;
  int iterations = 0;
  Descend(target, best, true, settings, ws, iterations);
  nominal_ = best;
}

LegWorkspace::LegWorkspace(const LegKinematics& leg)
    : chain_(leg.chain_ptr()),
      fk_(std::make_unique<KDL::ChainFkSolverPos_recursive>(*chain_)),
      q_(chain_->getNrOfJoints()),
      frames_(chain_->getNrOfSegments()),
      frames_B_(chain_->getNrOfSegments(), Eigen::Isometry3d::Identity()) {}

LegWorkspace::~LegWorkspace() = default;
LegWorkspace::LegWorkspace(LegWorkspace&&) noexcept = default;
LegWorkspace& LegWorkspace::operator=(LegWorkspace&&) noexcept = default;

}  // namespace stairplan
