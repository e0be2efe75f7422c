#include "planning/body/knot_row_cache.h"

#include <cmath>

namespace stairplan {
namespace {

// Two instants are the same knot when they agree to this [s] (cycles at multiples of the spacing
// agree exactly).
constexpr double kSameInstant = 1e-9;

// A row's relaxation coefficient at centre v0: the bound it breaks there minus its value, 0
// where it holds (BodyQp::KnotRows::sigma).
double Sigma(const Eigen::Vector4d& a, double lo, double hi, const Eigen::Vector4d& v0) {
  const double value = a.dot(v0);
  if (lo - value > 0.0) return lo - value;
  if (hi - value < 0.0) return hi - value;
  return 0.0;
}

}  // namespace

KnotRowCache::KnotRowCache(int knots, double dt, const Eigen::Vector4d& max_move)
    : dt_(dt), max_move_(max_move), slots_(static_cast<std::size_t>(knots + 1)) {}

std::size_t KnotRowCache::Index(double t) const {
  const long n = static_cast<long>(slots_.size());
  return static_cast<std::size_t>(((std::lround(t / dt_) % n) + n) % n);
}

const KnotRowCache::Slot* KnotRowCache::Find(double t) const {
  const Slot& slot = slots_[Index(t)];
  return slot.used && std::abs(slot.t - t) <= kSameInstant ? &slot : nullptr;
}

bool KnotRowCache::Restore(double t, const Eigen::Vector4d& v0, int k, BodyQp& qp, Eigen::Vector3d* q) const {
  const Slot* slot = Find(t);
  if (slot == nullptr || ((slot->v0 - v0).cwiseAbs().array() > max_move_.array()).any()) return false;
  const int stance = BodyQp::StanceRow(k, 0, 0), clearance = BodyQp::ClearanceRow(k, 0);
  for (int r = 0; r < kStance; ++r) {
    const Eigen::Vector4d a = slot->stance_a.row(r).transpose();
    qp.stance.a.row(stance + r) = a.transpose();
    qp.stance.lo[stance + r] = slot->stance_lo[r];
    qp.stance.hi[stance + r] = slot->stance_hi[r];
    qp.stance.sigma[stance + r] = Sigma(a, slot->stance_lo[r], slot->stance_hi[r], v0);
  }
  for (int r = 0; r < kClearance; ++r) {
    const Eigen::Vector4d a = slot->clearance_a.row(r).transpose();
    qp.clearance.a.row(clearance + r) = a.transpose();
    qp.clearance.lo[clearance + r] = slot->clearance_lo[r];
    qp.clearance.hi[clearance + r] = slot->clearance_hi[r];
    qp.clearance.sigma[clearance + r] = Sigma(a, slot->clearance_lo[r], slot->clearance_hi[r], v0);
  }
  for (int l = 0; l < kBodyLegs; ++l) q[l] = slot->q[static_cast<std::size_t>(l)];
  return true;
}

void KnotRowCache::Store(double t, const Eigen::Vector4d& v0, int k, const BodyQp& qp, const Eigen::Vector3d* q) {
  Slot& slot = slots_[Index(t)];
  const int stance = BodyQp::StanceRow(k, 0, 0), clearance = BodyQp::ClearanceRow(k, 0);
  slot.t = t;
  slot.used = true;
  slot.has_com = false;
  slot.v0 = v0;
  slot.stance_a = qp.stance.a.middleRows(stance, kStance);
  slot.stance_lo = qp.stance.lo.segment(stance, kStance);
  slot.stance_hi = qp.stance.hi.segment(stance, kStance);
  slot.clearance_a = qp.clearance.a.middleRows(clearance, kClearance);
  slot.clearance_lo = qp.clearance.lo.segment(clearance, kClearance);
  slot.clearance_hi = qp.clearance.hi.segment(clearance, kClearance);
  for (int l = 0; l < kBodyLegs; ++l) slot.q[static_cast<std::size_t>(l)] = q[l];
}

bool KnotRowCache::ComBase(double t, Eigen::Vector2d* com_base) const {
  const Slot* slot = Find(t);
  if (slot == nullptr || !slot->has_com) return false;
  *com_base = slot->com_base;
  return true;
}

void KnotRowCache::StoreComBase(double t, const Eigen::Vector2d& com_base) {
  Slot& slot = slots_[Index(t)];
  if (!slot.used || std::abs(slot.t - t) > kSameInstant) return;
  slot.com_base = com_base;
  slot.has_com = true;
}

}  // namespace stairplan
