// The leg rows' linearisations carried from one cycle to the next. The receding horizon advances
// one knot per cycle: knot k + 1 of the last cycle is knot k of this one, the same instant with
// the same footholds and swing positions, and its trust region's centre (the last plan there)
// has usually moved far less than the trust region allows. Its leg rows (KDL joints and
// extension, FCL clearances of the legs and the body) and its exact centre of mass are then
// taken over instead of solved again: linearised at a centre this near they differ by
// second-order terms, which the rows' clearance inset and joint margin cover. Where the centre
// moved more, or the cycle's instants fall between the last cycle's (a control loop whose period
// is not the knot spacing), the knot is linearised afresh. The clearance rows half a knot later
// (BodyQp::passing) are carried the same way, keyed by the instant their interval starts.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "stairplan/planning/body/body_qp.h"

namespace stairplan {

/// One cycle's leg rows per knot instant, reused by the next cycle at the same instant.
class KnotRowCache {
 public:
  /// Room for a horizon of `knots` knots `dt` apart; `max_move` is how far each of the centre's
  /// (z, pitch, shift, lateral) may move before a knot is linearised again. Allocates here only.
  KnotRowCache(int knots, double dt, const Eigen::Vector4d& max_move);

  /// Copies the rows linearised for instant `t` at a centre within max_move of `v0` into knot
  /// `k` of `qp` (their relaxation coefficients re-evaluated at `v0`) and the legs' joints into
  /// `q` (kBodyLegs of them); false, with nothing written, when there are none.
  bool Restore(double t, const Eigen::Vector4d& v0, int k, BodyQp& qp, Eigen::Vector3d* q) const;
  /// Keeps knot `k`'s rows of `qp`, linearised for instant `t` at centre `v0`, and the legs'
  /// joints `q` (kBodyLegs of them). Forgets that instant's centre of mass.
  void Store(double t, const Eigen::Vector4d& v0, int k, const BodyQp& qp, const Eigen::Vector3d* q);
  /// The centre of mass kept for instant `t` with its rows (ComBase's value), when there is one.
  bool ComBase(double t, Eigen::Vector2d* com_base) const;
  /// Keeps instant `t`'s centre of mass, computed at the centre its rows were stored with.
  void StoreComBase(double t, const Eigen::Vector2d& com_base);

  /// Copies the passing rows linearised for the interval starting at instant `t`, at a centre
  /// within max_move of `v0` and for at least the parts in `parts` (bit l: leg l's row, bit
  /// kBodyLegs: the body's), into interval `k` of `qp.passing`, their relaxation re-evaluated at
  /// `v0`; false, with nothing written, when there are none.
  bool RestorePassing(double t, const Eigen::Vector4d& v0, unsigned parts, int k, BodyQp& qp) const;
  /// Keeps interval `k`'s passing rows of `qp`, linearised for the parts in `parts` of the interval
  /// starting at instant `t`, at centre `v0`.
  void StorePassing(double t, const Eigen::Vector4d& v0, unsigned parts, int k, const BodyQp& qp);

 private:
  // One knot's N rows of a BodyQp::KnotRows family.
  template <int N>
  struct Rows {
    Eigen::Matrix<double, N, 4> a;
    Eigen::Matrix<double, N, 1> lo, hi;
  };
  struct Slot {
    double t = 0.0;
    bool used = false;
    bool has_com = false;
    Eigen::Vector4d v0 = Eigen::Vector4d::Zero();
    Rows<kBodyLegs * BodyQp::kStanceRows> stance;
    Rows<BodyQp::kClearanceRows> clearance;
    std::array<Eigen::Vector3d, kBodyLegs> q;
    Eigen::Vector2d com_base = Eigen::Vector2d::Zero();
  };
  // One interval's passing rows, in a ring of their own: they are taken over or linearised again
  // independently of the rows of the knot the interval starts at.
  struct PassingSlot {
    double t = 0.0;
    bool used = false;
    unsigned parts = 0;  // the legs (bit l) and the body (bit kBodyLegs) linearised
    Eigen::Vector4d v0 = Eigen::Vector4d::Zero();
    Rows<BodyQp::kClearanceRows> rows;
  };
  // Rows first .. first + N - 1 of `rows` into `kept`, and back (with the relaxation at `v0`).
  template <int N>
  static void ReadRows(const BodyQp::KnotRows& rows, int first, Rows<N>& kept);
  template <int N>
  static void WriteRows(const Rows<N>& kept, int first, const Eigen::Vector4d& v0, BodyQp::KnotRows& rows);
  // The slot of instant t (by its knot number t / dt, modulo the slots), and that slot of `ring`
  // when it holds instant t.
  std::size_t Index(double t) const;
  template <class S>
  const S* Find(const std::vector<S>& ring, double t) const;
  // Whether `v0` is within max_move of `kept`.
  bool Near(const Eigen::Vector4d& kept, const Eigen::Vector4d& v0) const;

  double dt_;
  Eigen::Vector4d max_move_;
  std::vector<Slot> slots_;
  std::vector<PassingSlot> passing_;
};

}  // namespace stairplan
