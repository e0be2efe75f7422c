// Reverse Cuthill-McKee over a pattern given as edges, component by component.
#include "stairplan/optim/band_ordering.h"

#include <algorithm>
#include <cstdlib>

namespace stairplan::optim {
namespace {

// A variable's new neighbours are few (on the body QP, 240 sorts of a handful each per
// ordering), where std::sort's setup per call cost more than the sorting: ranges up to this
// long are sorted by insertion, as libstdc++'s std::sort sorts them (stable), so the order is
// the same.
constexpr std::ptrdiff_t kInsertionSortMax = 16;

template <typename Less>
void InsertionSort(int* begin, int* end, Less less) {
  for (int* i = begin + (begin < end ? 1 : 0); i < end; ++i) {
    const int value = *i;
    int* j = i;
    for (; j > begin && less(value, *(j - 1)); --j) *j = *(j - 1);
    *j = value;
  }
}

}  // namespace

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
    int* begin = order->data() + first;
    int* end = order->data() + order->size();
    if (end - begin <= kInsertionSortMax) {
      InsertionSort(begin, end, by_degree);
    } else {
      std::sort(begin, end, by_degree);
    }
  }
  return order->back();
}

int BandOrdering::FarStart(int root) {
  probe_visited_ = visited_;
  probe_order_.clear();
  return Visit(root, &probe_visited_, &probe_order_);
}

int BandOrdering::Bandwidth(const std::vector<int>& position) const {
  // Four running maxima: one waited on the last at every edge.
  int width[4] = {0, 0, 0, 0};
  const std::size_t count = edges_.size();
  for (std::size_t e = 0; e < count; ++e) {
    const auto& [i, j] = edges_[e];
    int& w = width[e % 4];
    w = std::max(w, std::abs(position[static_cast<std::size_t>(i)] - position[static_cast<std::size_t>(j)]));
  }
  return std::max(std::max(width[0], width[1]), std::max(width[2], width[3]));
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
