#include "stairplan/planning/body/knot_row_cache.h"

#include <cmath>

namespace stairplan {
namespace {

// Two instants are the same knot when they agree to this [s] (cycles at multiples of the spacing
// agree exactly).
constexpr double kSameInstant = 1e-9;

}  // namespace

template <int N>
void KnotRowCache::ReadRows(const BodyQp::KnotRows& rows, int first, Rows<N>& kept) {
  kept.a = rows.a.middleRows(first, N);
  kept.lo = rows.lo.segment(first, N);
  kept.hi = rows.hi.segment(first, N);
}

template <int N>
void KnotRowCache::WriteRows(const Rows<N>& kept, int first, const Eigen::Vector4d& v0, BodyQp::KnotRows& rows) {
  rows.a.middleRows(first, N) = kept.a;
  rows.lo.segment(first, N) = kept.lo;
  rows.hi.segment(first, N) = kept.hi;
  rows.RelaxAt(first, N, v0);
}

KnotRowCache::KnotRowCache(int knots, double dt, const Eigen::Vector4d& max_move)
    : dt_(dt),
      max_move_(max_move),
      slots_(static_cast<std::size_t>(knots + 1)),
      passing_(static_cast<std::size_t>(knots + 1)) {}

std::size_t KnotRowCache::Index(double t) const {
  const long n = static_cast<long>(slots_.size());
  return static_cast<std::size_t>(((std::lround(t / dt_) % n) + n) % n);
}

template <class S>
const S* KnotRowCache::Find(const std::vector<S>& ring, double t) const {
  const S& slot = ring[Index(t)];
  return slot.used && std::abs(slot.t - t) <= kSameInstant ? &slot : nullptr;
}

bool KnotRowCache::Near(const Eigen::Vector4d& kept, const Eigen::Vector4d& v0) const {
  return ((kept - v0).cwiseAbs().array() <= max_move_.array()).all();
}

bool KnotRowCache::Restore(double t, const Eigen::Vector4d& v0, int k, BodyQp& qp, Eigen::Vector3d* q) const {
  const Slot* slot = Find(slots_, t);
  if (slot == nullptr || !Near(slot->v0, v0)) return false;
  WriteRows(slot->stance, BodyQp::StanceRow(k, 0, 0), v0, qp.stance);
  WriteRows(slot->clearance, BodyQp::ClearanceRow(k, 0), v0, qp.clearance);
  for (int l = 0; l < kBodyLegs; ++l) q[l] = slot->q[static_cast<std::size_t>(l)];
  return true;
}

void KnotRowCache::Store(double t, const Eigen::Vector4d& v0, int k, const BodyQp& qp, const Eigen::Vector3d* q) {
  Slot& slot = slots_[Index(t)];
  slot.t = t;
  slot.used = true;
  slot.has_com = false;
  slot.v0 = v0;
  ReadRows(qp.stance, BodyQp::StanceRow(k, 0, 0), slot.stance);
  ReadRows(qp.clearance, BodyQp::ClearanceRow(k, 0), slot.clearance);
  for (int l = 0; l < kBodyLegs; ++l) slot.q[static_cast<std::size_t>(l)] = q[l];
}

bool KnotRowCache::ComBase(double t, Eigen::Vector2d* com_base) const {
  const Slot* slot = Find(slots_, t);
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

bool KnotRowCache::RestorePassing(double t, const Eigen::Vector4d& v0, unsigned parts, int k, BodyQp& qp) const {
  const PassingSlot* slot = Find(passing_, t);
  if (slot == nullptr || (parts & ~slot->parts) != 0 || !Near(slot->v0, v0)) return false;
  const int first = BodyQp::ClearanceRow(k, 0);
  WriteRows(slot->rows, first, v0, qp.passing);
  // The parts linearised then but not asked for now have no row, as when linearised afresh.
  for (int part = 0; part < BodyQp::kClearanceRows; ++part) {
    if ((parts & (1u << part)) != 0) continue;
    qp.passing.lo[first + part] = -optim::kInf;
    qp.passing.sigma[first + part] = 0.0;
  }
  return true;
}

void KnotRowCache::StorePassing(double t, const Eigen::Vector4d& v0, unsigned parts, int k, const BodyQp& qp) {
  PassingSlot& slot = passing_[Index(t)];
  slot.t = t;
  slot.used = true;
  slot.parts = parts;
  slot.v0 = v0;
  ReadRows(qp.passing, BodyQp::ClearanceRow(k, 0), slot.rows);
}

}  // namespace stairplan
