// The kinematics of one leg as a KDL chain from the base link to the foot link: forward
// kinematics of the foot, the knee and every link frame, the foot Jacobian, position-only IK with
// joint limits, and reach. Model/workspace split as in Pinocchio: LegKinematics is const and
// shareable; each thread keeps a LegWorkspace, and no query allocates once the workspace exists.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <kdl/chain.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>

#include "stairplan/kinematics/leg_ik.h"
#include "stairplan/kinematics/robot_model.h"

namespace KDL {
class Tree;
class ChainFkSolverPos_recursive;
}  // namespace KDL

namespace stairplan {

class LegWorkspace;

/// Closed interval [lo, hi]; empty when lo > hi.
struct Interval1 {
  double lo = 1.0;  ///< lower end
  double hi = 0.0;  ///< upper end
  /// True when the interval holds no value (lo > hi).
  bool empty() const { return lo > hi; }
};

/// One leg's kinematics. All positions are in the base link's frame (suffix _B) and in metres.
class LegKinematics {
 public:
  /// Takes the chain base -> leg.foot_link out of `tree`. Throws std::invalid_argument naming the
  /// leg when the chain is missing or the leg does not have exactly 3 movable joints.
  LegKinematics(const LegModel& leg, const KDL::Tree& tree, const std::string& base_link);

  /// The leg as the robot model describes it.
  const LegModel& model() const { return leg_; }
  /// The leg's name: "LF", "RF", "LH" or "RH".
  const std::string& name() const { return leg_.name; }
  /// The KDL chain base -> foot link.
  const KDL::Chain& chain() const { return *chain_; }
  /// The same chain, shared (workspaces keep it alive).
  std::shared_ptr<const KDL::Chain> chain_ptr() const { return chain_; }
  /// Number of chain segments (fixed and movable), i.e. of link frames.
  int segment_count() const { return static_cast<int>(segment_links_.size()); }
  /// The link whose frame is the tip of segment i.
  const std::string& segment_link(int i) const { return segment_links_.at(static_cast<std::size_t>(i)); }
  /// Index of the segment whose frame sits on the knee (the last movable joint).
  int knee_segment() const { return knee_segment_; }

  /// Lower joint limits [rad].
  const Eigen::Vector3d& lower() const { return lower_; }
  /// Upper joint limits [rad].
  const Eigen::Vector3d& upper() const { return upper_; }
  /// A standing configuration: foot below the hip at 3/4 of reach().hi, knee pointing towards the
  /// body centre where the limits allow (ANYmal's front and hind knees bend opposite ways).
  const Eigen::Vector3d& nominal() const { return nominal_; }
  /// The first movable joint's origin (fixed in the base frame).
  const Eigen::Vector3d& hip_B() const { return hip_B_; }
  /// Sampled range of hip-to-foot distance over the joint limits [m].
  const Interval1& reach() const { return reach_; }

  /// Sampled range of the distance from the flexion joint (the second movable joint) to the foot
  /// over the knee's limits: the leg's extension, whatever the other joints do [m].
  const Interval1& extension() const { return extension_; }
  /// The flexion joint's position at q.
  Eigen::Vector3d FlexionPosition(const Eigen::Vector3d& q, LegWorkspace& ws) const;

  /// True when every joint is within [lower - tol, upper + tol].
  bool WithinLimits(const Eigen::Vector3d& q, double tol = 1e-9) const;
  /// q clamped into the limits.
  Eigen::Vector3d Clamp(const Eigen::Vector3d& q) const;

  /// Foot link origin.
  Eigen::Vector3d FootPosition(const Eigen::Vector3d& q, LegWorkspace& ws) const;
  /// Foot link pose.
  Eigen::Isometry3d FootPose(const Eigen::Vector3d& q, LegWorkspace& ws) const;
  /// Knee position (origin of the last movable joint's child frame).
  Eigen::Vector3d KneePosition(const Eigen::Vector3d& q, LegWorkspace& ws) const;
  /// Every segment's tip frame (link frame), index as segment_link(); the reference lives in `ws`.
  const std::vector<Eigen::Isometry3d>& LinkFrames(const Eigen::Vector3d& q, LegWorkspace& ws) const;
  /// Segment i's tip frame alone (LinkFrames(q, ws)[i] without converting the others).
  Eigen::Isometry3d LinkFrame(const Eigen::Vector3d& q, int i, LegWorkspace& ws) const;
  /// A movable joint's line in the base frame.
  struct JointLine {
    Eigen::Vector3d origin;  ///< a point on the line
    Eigen::Vector3d axis;    ///< its direction (unit length from JointLineAt)
    bool prismatic = false;  ///< the joint slides along the line rather than turning about it
  };
  /// Movable joint j's line in the base frame at q.
  JointLine JointLineAt(const Eigen::Vector3d& q, int j, LegWorkspace& ws) const;
  /// d(foot position)/dq, 3x3.
  Eigen::Matrix3d FootJacobian(const Eigen::Vector3d& q, LegWorkspace& ws) const;

  /// Joint angles putting the foot link origin at `foot_B`, starting from nominal().
  IkResult SolveFootIk(const Eigen::Vector3d& foot_B, LegWorkspace& ws, const IkSettings& settings = {}) const;
  /// The same from `seed` (clamped into the limits first). Throws std::invalid_argument on NaN input.
  IkResult SolveFootIk(const Eigen::Vector3d& foot_B, const Eigen::Vector3d& seed, LegWorkspace& ws,
                       const IkSettings& settings = {}) const;

 private:
  // One damped Gauss-Newton descent; `clamp` keeps the iterate within limits.
  double Descend(const Eigen::Vector3d& target, Eigen::Vector3d& q, bool clamp, const IkSettings& settings,
                 LegWorkspace& ws, int& iterations) const;
  Eigen::Vector3d RestartSeed(int k) const;
  // The forward kinematics at q, every segment's frame left in `ws` (kept there: a second call
  // at the same q costs a comparison); returns the foot.
  Eigen::Vector3d SegmentFrames(const Eigen::Vector3d& q, LegWorkspace& ws) const;
  // Fills fk_segments_ from the chain and keeps them where they reproduce KDL's frames.
  void BuildFkSegments(LegWorkspace& ws);
  // Whether the frames from fk_segments_ equal KDL's solver's within 1e-12 over the joints' ranges.
  bool FkSegmentsAgreeWithKdl(LegWorkspace& ws) const;
  // Movable joint j's line in the base frame, from the frames SegmentFrames left in `ws`.
  JointLine JointLineFromFrames(const LegWorkspace& ws, int j) const;
  // The foot Jacobian from the frames SegmentFrames left in `ws`: per joint, its axis crossed with
  // the lever from its origin to the foot (its axis alone for a prismatic joint).
  Eigen::Matrix3d JacobianFromFrames(const LegWorkspace& ws) const;
  // Moves `seed` into the basin of `target`: the knee angle whose hip-to-foot distance matches the
  // target's (from a table, the branch nearest the seed), then cyclic-coordinate-descent turns of
  // the flexion and abduction joints that point the foot at the target.
  Eigen::Vector3d AimedSeed(const Eigen::Vector3d& target, const Eigen::Vector3d& seed, LegWorkspace& ws) const;
  // True when the hip-to-foot distance is clearly outside reach(): no joint angles within the
  // limits reach it, whatever the seed.
  bool BeyondLimitedReach(const Eigen::Vector3d& foot_B) const;
  void BuildKneeTable(LegWorkspace& ws);
  void ComputeNominal(LegWorkspace& ws);
  void ComputeReach(LegWorkspace& ws);

  LegModel leg_;
  std::shared_ptr<const KDL::Chain> chain_;
  // Each chain segment for SegmentFrames: its frame at q = 0 and, for a revolute joint, its unit
  // axis and a point on it in the segment's base frame. An IK solve runs the chain tens of times
  // (hundreds when it fails and restarts), and these fixed-size products take 0.6 of KDL's
  // solver's time. Empty (a prismatic joint, frames KDL's solver disagrees with): KDL's solver.
  struct FkSegment {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    bool revolute = false;
  };
  std::vector<FkSegment> fk_segments_;
  std::vector<std::string> segment_links_;
  int knee_segment_ = 0;
  Eigen::Vector3d lower_, upper_, nominal_, hip_B_;
  Interval1 reach_;
  Interval1 extension_;
  std::array<int, 3> joint_segment_{};  // chain segment of each movable joint
  static constexpr int kKneeTable = 97;
  std::array<double, kKneeTable> knee_q_{}, knee_distance_{};  // foot distance from the flexion joint
};

/// Mutable scratch space of one leg's queries: KDL solvers and buffers, sized once.
class LegWorkspace {
 public:
  /// Sizes the solvers and buffers for `leg`; no query allocates afterwards.
  explicit LegWorkspace(const LegKinematics& leg);
  ~LegWorkspace();
  /// Moves the solvers and buffers.
  LegWorkspace(LegWorkspace&&) noexcept;
  /// Moves the solvers and buffers.
  LegWorkspace& operator=(LegWorkspace&&) noexcept;

 private:
  friend class LegKinematics;
  std::shared_ptr<const KDL::Chain> chain_;  // keeps the chain alive for the solvers
  std::unique_ptr<KDL::ChainFkSolverPos_recursive> fk_;
  KDL::JntArray q_;
  // Every segment's frame at frames_q_ (valid when frames_current_), and the same as Eigen
  // isometries (valid when frames_B_current_): queries at the q of the last one reuse them.
  std::vector<KDL::Frame> frames_;
  std::vector<Eigen::Isometry3d> frames_B_;
  Eigen::Vector3d frames_q_ = Eigen::Vector3d::Zero();
  bool frames_current_ = false;
  bool frames_B_current_ = false;
};

}  // namespace stairplan
