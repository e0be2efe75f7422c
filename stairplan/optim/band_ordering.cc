// Reverse Cuthill-McKee over a pattern given as edges, component by component.
#include "stairplan/optim/band_ordering.h"

#include <algorithm>
#include <cstdlib>

namespace stairplan::optim {

void BandOrdering::Reset(int n) {
  n_ = n;
  edges_.clear();
}

void BandOrdering::BuildAdjacency() {
  degree_.assign(static_cast<std::size_t>(n_), 0);
  for (const auto& [i, j] : edges_) {
    ++degree_[static_cast<std::size_t>(i)];
    ++degree_[static_cast<std::size_t>(j)];
  }
  start_.assign(static_cast<std::size_t>(n_) + 1, 0);
  for (int i = 0; i < n_; ++i) start_[i + 1] = start_[i] + degree_[static_cast<std::size_t>(i)];
  neighbours_.resize(static_cast<std::size_t>(start_[static_cast<std::size_t>(n_)]));
  // Filled from each variable's end backwards, the counts serving as cursors.
  std::vector<int>& cursor = position_;
  cursor.assign(start_.begin() + 1, start_.end());
  for (const auto& [i, j] : edges_) {
    neighbours_[static_cast<std::size_t>(--cursor[static_cast<std::size_t>(i)])] = j;
    neighbours_[static_cast<std::size_t>(--cursor[static_cast<std::size_t>(j)])] = i;
  }
}

int BandOrdering::Visit(int root, std::vector<char>* visited, std::vector<int>* order) const {
  std::size_t head = order->size();
  order->push_back(root);
  (*visited)[static_cast<std::size_t>(root)] = 1;
  while (head < order->size()) {
    const int v = (*order)[head++];
    const std::size_t first = order->size();
    for (int e = start_[static_cast<std::size_t>(v)]; e < start_[static_cast<std::size_t>(v) + 1]; ++e) {
      const int u = neighbours_[static_cast<std::size_t>(e)];
      if ((*visited)[static_cast<std::size_t>(u)]) continue;
      (*visited)[static_cast<std::size_t>(u)] = 1;
      order->push_back(u);
    }
    const auto by_degree = [this](int a, int b) {
      return degree_[static_cast<std::size_t>(a)] < degree_[static_cast<std::size_t>(b)];
    };
    std::sort(order->begin() + static_cast<std::ptrdiff_t>(first), order->end(), by_degree);
  }
  return order->back();
}

int BandOrdering::FarStart(int root) {
  probe_visited_ = visited_;
  probe_order_.clear();
  return Visit(root, &probe_visited_, &probe_order_);
}

int BandOrdering::Bandwidth(const std::vector<int>& position) const {
  int width = 0;
  for (const auto& [i, j] : edges_) {
    width = std::max(width, std::abs(position[static_cast<std::size_t>(i)] - position[static_cast<std::size_t>(j)]));
  }
  return width;
}

void BandOrdering::Compute() {
  BuildAdjacency();
  visited_.assign(static_cast<std::size_t>(n_), 0);
  order_.clear();
  for (int root = 0; root < n_; ++root) {
    if (!visited_[static_cast<std::size_t>(root)]) Visit(FarStart(root), &visited_, &order_);
  }
  std::reverse(order_.begin(), order_.end());
  position_.resize(static_cast<std::size_t>(n_));
  for (int k = 0; k < n_; ++k) position_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])] = k;
  const int reversed = Bandwidth(position_);
  for (int k = 0; k < n_; ++k) order_[static_cast<std::size_t>(k)] = k;
  const int given = Bandwidth(order_);
  reordered_ = reversed < given;
  if (!reordered_) position_.swap(order_);
  bandwidth_ = std::min(reversed, given);
}

void BandOrdering::KeepDense() {
  position_.resize(static_cast<std::size_t>(n_));
  for (int k = 0; k < n_; ++k) position_[static_cast<std::size_t>(k)] = k;
  reordered_ = false;
  bandwidth_ = std::max(0, n_ - 1);
}

}  // namespace stairplan::optim
