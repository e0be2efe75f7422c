// BandOrdering: a permutation of a symmetric matrix's rows and columns that keeps its nonzeros
// near the diagonal, from its sparsity pattern (reverse Cuthill-McKee; George & Liu, Computer
// Solution of Large Sparse Positive Definite Systems, 1981, chapter 4).
//
// Why: a Program's variables come in blocks by quantity (every knot's height, then every knot's
// pitch, ...), so the interior-point solver's Newton matrix couples variable i with i + knots:
// wide in the program's order, narrow once ordered knot by knot. Reverse Cuthill-McKee finds
// that order from the pattern alone, without knowing what a knot is. The program's own order is
// kept when it is at least as narrow. Workspace only grows: no allocation for a pattern of the
// same size or smaller.
//
//   BandOrdering o;
//   o.Reset(n);  o.AddEdge(i, j); ...;   // the off-diagonal nonzeros (either triangle, repeats fine)
//   o.Compute();
//   o.position(i);  o.bandwidth();       // where variable i goes; the half-bandwidth in that order
#pragma once

#include <utility>
#include <vector>

namespace stairplan::optim {

/// Reverse Cuthill-McKee ordering of a symmetric pattern, or the given order when it is narrower.
class BandOrdering {
 public:
  /// Starts a pattern of n variables with no edges.
  void Reset(int n);
  /// Room for `edges` edges (a caller that knows how many spares their growth one by one).
  void Reserve(std::size_t edges) { edges_.reserve(edges); }
  /// Variables i and j are coupled (an off-diagonal nonzero; i == j is ignored).
  void AddEdge(int i, int j) {
    if (i != j) edges_.emplace_back(i, j);
  }
  /// Orders the variables: reverse Cuthill-McKee, or the identity when that is no narrower.
  void Compute();
  /// Keeps the given order with the full band (n - 1): for patterns too dense to be worth ordering.
  void KeepDense();
  /// Edges added since Reset().
  std::size_t edges() const { return edges_.size(); }

  /// The position of variable i in the new order.
  int position(int i) const { return position_[static_cast<std::size_t>(i)]; }
  /// The half-bandwidth of the pattern in the new order.
  int bandwidth() const { return bandwidth_; }
  /// True when the order is not the identity.
  bool reordered() const { return reordered_; }

 private:
  void BuildAdjacency();
  // Breadth-first search from `root` over the unvisited variables, each one's neighbours by
  // increasing degree, appended to `order`; returns the last variable reached (a far one).
  int Visit(int root, std::vector<char>* visited, std::vector<int>* order) const;
  // A start far from the rest of root's component (George & Liu's pseudo-peripheral node, one pass).
  int FarStart(int root);
  int Bandwidth(const std::vector<int>& position) const;

  int n_ = 0;
  int bandwidth_ = 0;
  bool reordered_ = false;
  std::vector<std::pair<int, int>> edges_;
  std::vector<int> start_, neighbours_, degree_;  // the adjacency in compressed rows
  std::vector<int> order_, probe_order_, position_;
  std::vector<char> visited_, probe_visited_;
};

}  // namespace stairplan::optim
