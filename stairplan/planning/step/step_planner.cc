#include "stairplan/planning/step/step_planner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "stairplan/geometry/field_error.h"
#include "stairplan/planning/step/step_height.h"

namespace stairplan {
namespace {

constexpr double kTieTolerance = 1e-9;
constexpr int kMaxCandidates = 17;  // nearest stair and up to 8 on either side

bool Finite(const Eigen::Vector2d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// The pair a role belongs to (0 rear, 1 fore) and the other role of that pair.
int PairOf(TravelRole r) { return (r == TravelRole::kRearRight || r == TravelRole::kRearLeft) ? 0 : 1; }

// The leading role of each pair: the one that swings first in the gait ([0070]).
std::array<TravelRole, 2> Leaders(const GaitPattern& pattern) {
  std::array<TravelRole, 2> leaders{};
  std::array<bool, 2> found{false, false};
  for (int p = 0; p < pattern.phases; ++p) {
    for (int i = 0; i < pattern.legs_per_phase; ++i) {
      const TravelRole r = pattern.phase_roles[static_cast<std::size_t>(p)][static_cast<std::size_t>(i)];
      const int pair = PairOf(r);
      if (!found[static_cast<std::size_t>(pair)]) {
        found[static_cast<std::size_t>(pair)] = true;
        leaders[static_cast<std::size_t>(pair)] = r;
      }
    }
  }
  return leaders;
}

}  // namespace

const char* ToString(RuleOut reason) {
  switch (reason) {
    case RuleOut::kNone: return "none";
    case RuleOut::kNoStepRegion: return "no step region";
    case RuleOut::kStepTooHigh: return "step too high";
    case RuleOut::kUnreachable: return "unreachable";
    case RuleOut::kStanceLost: return "stance foot lost";
    case RuleOut::kLeaderBehind: return "leading leg behind";
    case RuleOut::kStepsBack: return "steps back";
  }
  return "unknown";
}

StepPlanner::StepPlanner(const RobotModel& robot, const ConstrainedMap& map, const StepPlannerSettings& settings,
                         std::shared_ptr<const ReachModel> reach)
    : legs_(robot.legs()), map_(map), settings_(settings), reach_(std::move(reach)) {
  settings_.Validate();
  if (legs_.size() != 4) throw std::invalid_argument("StepPlanner: robot: needs exactly four legs");
  if (map_.size() < 1) throw std::invalid_argument("StepPlanner: map: has no surfaces");
  if (!reach_) reach_ = std::make_shared<GeometricReachModel>(settings_.reach_min_fraction, settings_.reach_max_fraction);
  ground_ = GroundProfile::FromMap(map_);
  yaw_ = map_.facing() == Facing::kForward ? 0.0 : M_PI;
  cos_yaw_ = std::cos(yaw_);
  sin_yaw_ = std::sin(yaw_);
  const double c = cos_yaw_;

  // Roles relative to travel: facing backwards, the body's front legs are the rear ones.
  leg_of_role_.fill(-1);
  double reach_sum = 0.0, fore_x = 0.0, hind_x = 0.0;
  int fore_n = 0, hind_n = 0;
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    const LegModel& leg = legs_[i];
    if (!(leg.max_reach > 0.0)) throw std::invalid_argument("StepPlanner: robot: leg " + leg.name + " has no reach");
    const bool fore = c * leg.hip_B.x() > 0.0;
    const bool right = c * leg.hip_B.y() < 0.0;
    const TravelRole role = fore ? (right ? TravelRole::kForeRight : TravelRole::kForeLeft)
                                 : (right ? TravelRole::kRearRight : TravelRole::kRearLeft);
    if (leg_of_role_[static_cast<std::size_t>(role)] >= 0) {
      throw std::invalid_argument("StepPlanner: robot: two legs (" + legs_[static_cast<std::size_t>(leg_of_role_[static_cast<std::size_t>(role)])].name +
                                  ", " + leg.name + ") at the same corner");
    }
    leg_of_role_[static_cast<std::size_t>(role)] = static_cast<int>(i);
    role_of_leg_[i] = static_cast<int>(role);
    neutral_offset_W_[i] = Eigen::Rotation2Dd(yaw_) * Eigen::Vector2d(leg.hip_B.x(), leg.foot_zero_B.y());
    max_step_height_[i] = MaxStepHeight(leg, settings_);
    reach_sum += leg.max_reach;
    mean_hip_z_ += leg.hip_B.z() / 4.0;
    mean_foot_radius_ += leg.foot_radius / 4.0;
    if (leg.hip_B.x() > 0.0) {
      fore_x += leg.hip_B.x();
      ++fore_n;
    } else {
      hind_x += leg.hip_B.x();
      ++hind_n;
    }
  }
  if (fore_n != 2 || hind_n != 2) throw std::invalid_argument("StepPlanner: robot: needs two front and two hind legs");
  fore_hip_x_B_ = fore_x / 2.0;
  hind_hip_x_B_ = hind_x / 2.0;
  hip_height_ = settings_.hip_height_fraction * reach_sum / 4.0 + mean_foot_radius_;

  for (const StairRegions& s : map_.stairs()) {
    RegionInfo info;
    info.z = s.z;
    if (!s.step_region.empty()) {
      info.present = true;
      info.x_lo = info.y_lo = std::numeric_limits<double>::infinity();
      info.x_hi = info.y_hi = -std::numeric_limits<double>::infinity();
      for (const auto& v : s.step_region.vertices) {
        info.x_lo = std::min(info.x_lo, v.x());
        info.x_hi = std::max(info.x_hi, v.x());
        info.y_lo = std::min(info.y_lo, v.y());
        info.y_hi = std::max(info.y_hi, v.y());
        info.centroid += v / static_cast<double>(s.step_region.vertices.size());
      }
      // An axis-aligned rectangle (what the analytic map makes) is inset exactly; other convex
      // regions are handled by pulling the closest point towards the centroid.
      info.rectangle = s.step_region.vertices.size() == 4;
      for (const auto& v : s.step_region.vertices) {
        const bool on_x = std::abs(v.x() - info.x_lo) < 1e-12 || std::abs(v.x() - info.x_hi) < 1e-12;
        const bool on_y = std::abs(v.y() - info.y_lo) < 1e-12 || std::abs(v.y() - info.y_hi) < 1e-12;
        info.rectangle = info.rectangle && on_x && on_y;
      }
      const double mx = std::min(settings_.target_margin, 0.45 * (info.x_hi - info.x_lo));
      const double my = std::min(settings_.target_margin, 0.45 * (info.y_hi - info.y_lo));
      info.in_x_lo = info.x_lo + mx;
      info.in_x_hi = info.x_hi - mx;
      info.in_y_lo = info.y_lo + my;
      info.in_y_hi = info.y_hi - my;
    }
    regions_.push_back(info);
    double x_end = -std::numeric_limits<double>::infinity();
    for (const auto& v : s.surface.vertices) x_end = std::max(x_end, v.x());
    surface_x_end_.push_back(x_end);
  }

  for (Gait gait : settings_.gaits) {
    for (double cadence : settings_.cadences_s) controllers_.push_back({cadence, gait});
  }
  evaluations_.resize(controllers_.size());
  // Liftoff and touchdown instants: up to horizon_steps + 1 swings from now.
  pose_stride_ = static_cast<std::size_t>(settings_.horizon_steps) + 1;
  poses_.resize(settings_.cadences_s.size() * pose_stride_);
  end_poses_.resize(settings_.cadences_s.size() * static_cast<std::size_t>(settings_.horizon_steps));
  for (const FixedCadenceController& controller : controllers_) {
    longest_stance_s_ = std::max(longest_stance_s_, PatternOf(controller.gait).stance_in_swings() * controller.cadence_s);
  }
  for (ControllerEvaluation& e : evaluations_) e.steps.resize(static_cast<std::size_t>(settings_.horizon_steps));
}

const ControllerEvaluation& StepPlanner::evaluation(int index) const {
  if (index < 0 || index >= static_cast<int>(evaluations_.size())) {
    throw std::invalid_argument("StepPlanner::evaluation: index " + std::to_string(index) + " out of range");
  }
  return evaluations_[static_cast<std::size_t>(index)];
}

std::string StepPlanner::RuleOutReason(int index) const {
  const ControllerEvaluation& e = evaluation(index);
  if (e.rule_out == RuleOut::kNone) return "";
  const PlannedStep& s = e.steps[static_cast<std::size_t>(std::max(0, e.rule_out_step))];
  const std::string leg = s.leg >= 0 ? legs_[static_cast<std::size_t>(s.leg)].name : "?";
  const std::string where = "footstep " + std::to_string(e.rule_out_step + 1) + " (" + leg + ")";
  char value[64];
  switch (e.rule_out) {
    case RuleOut::kNoStepRegion: return where + ": no step region in the map";
    case RuleOut::kStepTooHigh:
      std::snprintf(value, sizeof value, "%.3f m > %.3f m", e.rule_out_value, max_step_height_[static_cast<std::size_t>(std::max(0, s.leg))]);
      return where + ": step height " + value + " the leg can clear";
    case RuleOut::kUnreachable:
      std::snprintf(value, sizeof value, "%.2f", e.rule_out_value);
      return where + ": no target in reach (hip-to-foot " + value + " of max_reach)";
    case RuleOut::kLeaderBehind: return where + ": the leading leg would land behind its trailing leg";
    case RuleOut::kStanceLost:
      std::snprintf(value, sizeof value, "%.2f", e.rule_out_value);
      return where + ": its stance foot falls out of reach before liftoff (hip-to-foot " + value + " of max_reach)";
    case RuleOut::kStepsBack: return where + ": the only targets lie behind the leg's stair";
    case RuleOut::kNone: break;
  }
  return "";
}

double StepPlanner::BodyPitchAt(const Eigen::Vector2d& body_xy_W) const {
  const double c = std::cos(yaw_);
  const double g_fore = ground_.HeightAt(body_xy_W.x() + c * fore_hip_x_B_);
  const double g_hind = ground_.HeightAt(body_xy_W.x() + c * hind_hip_x_B_);
  return -std::atan2(g_fore - g_hind, fore_hip_x_B_ - hind_hip_x_B_);
}

Eigen::Isometry3d StepPlanner::BodyPoseAt(const Eigen::Vector2d& body_xy_W) const {
  const double cy = cos_yaw_, sy = sin_yaw_;
  const double g_fore = ground_.HeightAt(body_xy_W.x() + cy * fore_hip_x_B_);
  const double g_hind = ground_.HeightAt(body_xy_W.x() + cy * hind_hip_x_B_);
  // pitch = -atan2(rise, length) along the hips; its sine and cosine without trigonometry, since
  // this runs for every footstep of every controller. R = Rz(yaw) * Ry(pitch), written out.
  const double rise = g_fore - g_hind, length = fore_hip_x_B_ - hind_hip_x_B_;
  const double hyp = std::sqrt(rise * rise + length * length);
  const double sp = -rise / hyp, cp = length / hyp;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << cy * cp, -sy, cy * sp,
                   sy * cp, cy, sy * sp,
                   -sp, 0.0, cp;
  pose.translation() = Eigen::Vector3d(body_xy_W.x(), body_xy_W.y(), 0.5 * (g_fore + g_hind) + hip_height_ - mean_hip_z_);
  return pose;
}

Eigen::Vector2d StepPlanner::NeutralFootXY(int leg, const Eigen::Vector2d& body_xy_W) const {
  return body_xy_W + neutral_offset_W_.at(static_cast<std::size_t>(leg));
}

double StepPlanner::RegionDistance(int k, const Eigen::Vector2d& p) const {
  const RegionInfo& r = regions_[static_cast<std::size_t>(k)];
  if (r.rectangle) {
    const double dx = std::max({r.x_lo - p.x(), 0.0, p.x() - r.x_hi});
    const double dy = std::max({r.y_lo - p.y(), 0.0, p.y() - r.y_hi});
    return std::sqrt(dx * dx + dy * dy);
  }
  return map_.stairs()[static_cast<std::size_t>(k)].step_region.Distance(p);
}

int StepPlanner::NearestRegion(const Eigen::Vector2d& p, double* distance) const {
  const int n = static_cast<int>(regions_.size());
  // Start at the surface under p (surfaces are sorted along x) and widen while a closer region
  // is still possible along x.
  int start = static_cast<int>(std::lower_bound(surface_x_end_.begin(), surface_x_end_.end(), p.x()) - surface_x_end_.begin());
  start = std::clamp(start, 0, n - 1);
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  const auto consider = [&](int k) {
    const RegionInfo& r = regions_[static_cast<std::size_t>(k)];
    if (!r.present) return;
    const double d = RegionDistance(k, p);
    if (d < best_d - kTieTolerance || (std::abs(d - best_d) <= kTieTolerance && k < best)) {
      best_d = d;
      best = k;
    }
  };
  consider(start);
  for (int k = start - 1; k >= 0; --k) {
    const RegionInfo& r = regions_[static_cast<std::size_t>(k)];
    if (r.present && p.x() - r.x_hi > best_d) break;
    consider(k);
  }
  for (int k = start + 1; k < n; ++k) {
    const RegionInfo& r = regions_[static_cast<std::size_t>(k)];
    if (r.present && r.x_lo - p.x() > best_d) break;
    consider(k);
  }
  if (distance != nullptr) *distance = best_d;
  return best;
}

Eigen::Vector2d StepPlanner::SnapIntoRegion(int stair, const Eigen::Vector2d& p) const {
  const RegionInfo& r = regions_.at(static_cast<std::size_t>(stair));
  if (!r.present) return p;
  if (r.rectangle) return {std::clamp(p.x(), r.in_x_lo, r.in_x_hi), std::clamp(p.y(), r.in_y_lo, r.in_y_hi)};
  const Eigen::Vector2d q = map_.stairs()[static_cast<std::size_t>(stair)].step_region.ClosestPoint(p);
  const Eigen::Vector2d to_centre = r.centroid - q;
  const double len = to_centre.norm();
  if (len <= 1e-12) return q;
  return q + to_centre * (std::min(settings_.target_margin, 0.5 * len) / len);
}

int StepPlanner::Update(const StepPlannerInput& input) {
  if (!std::isfinite(input.now_s) || !Finite(input.body_xy_W) || !Finite(input.velocity_W)) {
    throw std::invalid_argument("StepPlanner::Update: input: now_s, body_xy_W and velocity_W must be finite");
  }
  for (const StepLegState& leg : input.legs) {
    if (!leg.foot_W.allFinite() || !std::isfinite(leg.last_touchdown_s)) {
      throw std::invalid_argument("StepPlanner::Update: input.legs: foot_W and last_touchdown_s must be finite");
    }
  }
  // Base poses at the instants the plans use, shared by the gaits of one cadence: after j swings
  // (liftoffs and touchdowns), and after a touchdown plus the longest stance any controller gives
  // (a foot placed now must stay in reach however long later choices keep it down).
  const std::size_t horizon = static_cast<std::size_t>(settings_.horizon_steps);
  for (std::size_t c = 0; c < settings_.cadences_s.size(); ++c) {
    const double T = settings_.cadences_s[c];
    for (std::size_t j = 0; j < pose_stride_; ++j) {
      poses_[c * pose_stride_ + j] = BodyPoseAt(input.body_xy_W + input.velocity_W * (static_cast<double>(j) * T));
    }
    for (std::size_t p = 0; p < horizon; ++p) {
      end_poses_[c * horizon + p] = BodyPoseAt(input.body_xy_W + input.velocity_W * (static_cast<double>(p + 1) * T + longest_stance_s_));
    }
  }
  const int count = static_cast<int>(controllers_.size());
  for (int i = 0; i < count; ++i) Evaluate(i, input);
  int best = -1;
  for (int i = 0; i < count; ++i) {
    const ControllerEvaluation& e = evaluations_[static_cast<std::size_t>(i)];
    if (!e.admissible) continue;
    // Lower index wins ties because the loop runs in index order and needs a strict improvement.
    if (best < 0 || e.score < evaluations_[static_cast<std::size_t>(best)].score - kTieTolerance) best = i;
  }
  // The current controller keeps its place on a tie (it already carries no switch cost).
  if (best >= 0 && selected_ >= 0 && selected_ != best) {
    const ControllerEvaluation& current = evaluations_[static_cast<std::size_t>(selected_)];
    if (current.admissible && current.score <= evaluations_[static_cast<std::size_t>(best)].score + kTieTolerance) best = selected_;
  }
  selected_ = best;
  return best;
}

void StepPlanner::Evaluate(int index, const StepPlannerInput& input) {
  const FixedCadenceController& controller = controllers_[static_cast<std::size_t>(index)];
  ControllerEvaluation& e = evaluations_[static_cast<std::size_t>(index)];
  const GaitPattern& pattern = PatternOf(controller.gait);
  const std::array<TravelRole, 2> leaders = Leaders(pattern);
  const double T = controller.cadence_s;
  const double stance = pattern.stance_in_swings() * T;
  e.admissible = true;
  e.score = 0.0;
  e.rule_out = RuleOut::kNone;
  e.rule_out_step = -1;
  e.rule_out_value = 0.0;
  e.region_cost = e.snap_cost = e.trailing_cost = e.swing_height_cost = e.reach_cost = e.timing_cost = e.switch_cost = 0.0;
  e.step_count = 0;

  // The first phase swings the leg that has stood longest (ties: the earlier phase), so that
  // switching controllers keeps the legs' rotation.
  int first_phase = 0;
  double oldest = std::numeric_limits<double>::infinity();
  for (int p = 0; p < pattern.phases; ++p) {
    for (int i = 0; i < pattern.legs_per_phase; ++i) {
      const int leg = leg_of_role_[static_cast<std::size_t>(pattern.phase_roles[static_cast<std::size_t>(p)][static_cast<std::size_t>(i)])];
      const double t = input.legs[static_cast<std::size_t>(leg)].last_touchdown_s;
      if (t < oldest - kTieTolerance) {
        oldest = t;
        first_phase = p;
      }
    }
  }

  // Every event of this plan happens a whole number of swings from now: liftoff after p swings,
  // touchdown after p + 1 (poses computed once per cadence in Update).
  const std::size_t cadence = static_cast<std::size_t>(index) % settings_.cadences_s.size();
  const Eigen::Isometry3d* poses = &poses_[cadence * pose_stride_];
  const Eigen::Isometry3d* end_poses = &end_poses_[cadence * static_cast<std::size_t>(settings_.horizon_steps)];

  std::array<Eigen::Vector3d, 4> foot;
  std::array<int, 4> stair;
  for (std::size_t l = 0; l < 4; ++l) {
    foot[l] = input.legs[l].foot_W;
    stair[l] = input.legs[l].stair;
  }
  const int horizon = settings_.horizon_steps;
  for (int k = 0; k < horizon; ++k) {
    const int phase_step = k / pattern.legs_per_phase;
    const int phase = (first_phase + phase_step) % pattern.phases;
    const TravelRole role = pattern.phase_roles[static_cast<std::size_t>(phase)][static_cast<std::size_t>(k % pattern.legs_per_phase)];
    const int leg = leg_of_role_[static_cast<std::size_t>(role)];
    const std::size_t l = static_cast<std::size_t>(leg);
    const LegModel& model = legs_[l];
    PlannedStep& s = e.steps[static_cast<std::size_t>(k)];
    s.leg = leg;
    s.t_liftoff = input.now_s + phase_step * T;
    s.t_touchdown = s.t_liftoff + T;
    s.from_W = foot[l];
    s.from_stair = stair[l];
    s.rule_out = RuleOut::kNone;
    const Eigen::Isometry3d& base_lift = poses[phase_step];
    const Eigen::Isometry3d& base_td = poses[phase_step + 1];
    const Eigen::Isometry3d& base_end = end_poses[phase_step];
    // The unconstrained footstep: under the hip at mid-stance of the coming stance phase.
    const Eigen::Vector2d body_td = base_td.translation().head<2>();
    s.unconstrained_xy_W = body_td + neutral_offset_W_[l] + input.velocity_W * (0.5 * stance);
    s.nearest_stair = NearestRegion(s.unconstrained_xy_W, &s.region_distance);
    e.step_count = k + 1;
    if (s.nearest_stair < 0) {
      e.rule_out = s.rule_out = RuleOut::kNoStepRegion;
      e.rule_out_step = k;
      break;
    }
    // The foot it stands on must stay in reach until this controller lifts it.
    const Eigen::Vector3d stance_centre = foot[l] + Eigen::Vector3d(0.0, 0.0, model.foot_radius);
    if (!reach_->Reachable(model, base_lift, stance_centre)) {
      e.rule_out = s.rule_out = RuleOut::kStanceLost;
      e.rule_out_step = k;
      e.rule_out_value = GeometricReachModel::Extension(model, base_lift, stance_centre);
      break;
    }

    // Candidate stairs: the nearest region and its neighbours, closest first.
    std::array<std::pair<double, int>, kMaxCandidates> candidates;
    int n_candidates = 0;
    const int n_stairs = static_cast<int>(regions_.size());
    for (int dk = -settings_.candidate_stairs; dk <= settings_.candidate_stairs; ++dk) {
      const int c = s.nearest_stair + dk;
      if (c < 0 || c >= n_stairs || !regions_[static_cast<std::size_t>(c)].present) continue;
      const double d = dk == 0 ? s.region_distance : RegionDistance(c, s.unconstrained_xy_W);
      candidates[static_cast<std::size_t>(n_candidates++)] = {d, c};
    }
    for (int i = 1; i < n_candidates; ++i) {  // insertion sort: at most 2 * candidate_stairs + 1
      for (int j = i; j > 0 && candidates[static_cast<std::size_t>(j)] < candidates[static_cast<std::size_t>(j - 1)]; --j) {
        std::swap(candidates[static_cast<std::size_t>(j)], candidates[static_cast<std::size_t>(j - 1)]);
      }
    }

    // Leading and trailing legs ([0070]): when a leading leg lands on a stair, its trailing leg
    // stands on that stair or one below it in travel order (hard); a trailing leg prefers not to
    // pass its leading leg, and does so (at trailing_cost) only when nothing else is in reach.
    const int pair = PairOf(role);
    const TravelRole leader_role = leaders[static_cast<std::size_t>(pair)];
    const bool leading = role == leader_role;
    const TravelRole partner_role = pair == 0 ? (role == TravelRole::kRearRight ? TravelRole::kRearLeft : TravelRole::kRearRight)
                                              : (role == TravelRole::kForeRight ? TravelRole::kForeLeft : TravelRole::kForeRight);
    const int partner_stair = stair[static_cast<std::size_t>(leg_of_role_[static_cast<std::size_t>(partner_role)])];

    RuleOut first_reason = RuleOut::kNone;
    double first_value = 0.0;
    bool placed = false;
    for (int pass = 0; pass < 2 && !placed; ++pass) {
      const bool keep_behind = pass == 0 && !leading && partner_stair >= 0;
      for (int ci = 0; ci < n_candidates && !placed; ++ci) {
        const int c = candidates[static_cast<std::size_t>(ci)].second;
        if (keep_behind && c > partner_stair) continue;
        RuleOut reason = RuleOut::kNone;
        double value = 0.0;
        double effort = 0.0;
        const Eigen::Vector2d xy = SnapIntoRegion(c, s.unconstrained_xy_W);
        const Eigen::Vector3d target(xy.x(), xy.y(), regions_[static_cast<std::size_t>(c)].z);
        const double step_height = std::abs(target.z() - foot[l].z());
        if (stair[l] >= 0 && c < stair[l]) {
          reason = RuleOut::kStepsBack;  // stepping back down the flight is never planned
        } else if (leading && partner_stair >= 0 && c < partner_stair) {
          reason = RuleOut::kLeaderBehind;
        } else if (step_height > max_step_height_[l]) {
          reason = RuleOut::kStepTooHigh;
          value = step_height;
        } else {
          const Eigen::Vector3d foot_centre = target + Eigen::Vector3d(0.0, 0.0, model.foot_radius);
          if (!reach_->Reachable(model, base_td, foot_centre)) {
            reason = RuleOut::kUnreachable;
            value = GeometricReachModel::Extension(model, base_td, foot_centre);
          } else if (!reach_->Reachable(model, base_end, foot_centre)) {
            reason = RuleOut::kUnreachable;
            value = GeometricReachModel::Extension(model, base_end, foot_centre);
          } else {
            effort = reach_->Effort(model, base_td, foot_centre);
          }
        }
        if (pass == 1 && ci == 0) {
          first_reason = reason;
          first_value = value;
        }
        if (reason != RuleOut::kNone) continue;
        placed = true;
        s.target_W = target;
        s.target_stair = c;
        const double snap = (xy - s.unconstrained_xy_W).norm();
        e.region_cost += settings_.region_weight * s.region_distance;
        e.snap_cost += settings_.snap_weight * std::max(0.0, snap - s.region_distance);
        if (!leading && partner_stair >= 0 && c > partner_stair) e.trailing_cost += settings_.trailing_cost;
        e.reach_cost += settings_.reach_weight * effort * effort;
        const double height_ratio = step_height / max_step_height_[l];
        e.swing_height_cost += settings_.swing_height_weight * height_ratio * height_ratio;
        const double excess = std::max(0.0, (target - foot[l]).norm() / T - settings_.max_foot_speed);
        e.timing_cost += settings_.timing_weight * excess * excess;
      }
    }
    if (!placed) {
      e.rule_out = s.rule_out = first_reason == RuleOut::kNone ? RuleOut::kUnreachable : first_reason;
      e.rule_out_step = k;
      e.rule_out_value = first_value;
      break;
    }
    foot[l] = s.target_W;
    stair[l] = s.target_stair;
  }
  if (e.rule_out != RuleOut::kNone) {
    e.admissible = false;
    e.score = std::numeric_limits<double>::infinity();
    return;
  }
  // Hysteresis: another cadence costs a little, another gait more (it reorders the legs mid-cycle).
  e.switch_cost = 0.0;
  if (selected_ >= 0 && selected_ != index) {
    e.switch_cost = settings_.switch_cost;
    if (controllers_[static_cast<std::size_t>(selected_)].gait != controller.gait) e.switch_cost += settings_.gait_switch_cost;
  }
  e.score = e.region_cost + e.snap_cost + e.trailing_cost + e.swing_height_cost + e.reach_cost + e.timing_cost + e.switch_cost;
}

}  // namespace stairplan
