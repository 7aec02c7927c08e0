// Broad phase of the folding check (fold_check.cpp): every pair of axis-aligned 3D boxes that
// meet as closed boxes (touching counts), by a sweep along x. The set is the one CGAL's
// box_self_intersection_d reports with its default (closed) topology; the pairs come sorted
// (p < q, lexicographic), so the result does not depend on the sweep. The sweep order (boxes by
// low x, ties by index) is kept from one call to the next: the folding check's boxes move
// little per step, so an insertion sort restores it in about linear time.
#pragma once
#include <algorithm>
#include <utility>
#include <vector>

namespace dcshell::unfold_detail {

class BoxSweep {
 public:
  /// lo, hi: 3 doubles per box (box b at 3b .. 3b + 2); every box has lo <= hi.
  void pairs(const std::vector<double>& lo, const std::vector<double>& hi, std::vector<std::pair<int, int>>& out) {
    const int n = static_cast<int>(lo.size() / 3);
    if (static_cast<int>(order_.size()) != n) {
      order_.resize(n);
      for (int b = 0; b < n; ++b) order_[b] = b;
    }
    std::vector<int>& s = order_;
    auto before = [&](int a, int b) { return lo[3 * a] < lo[3 * b] || (lo[3 * a] == lo[3 * b] && a < b); };
    for (int i = 1; i < n; ++i) {
      const int x = s[i];
      int j = i;
      for (; j > 0 && before(x, s[j - 1]); --j) s[j] = s[j - 1];
      s[j] = x;
    }
    // The boxes' coordinates in sweep order, one array per bound: the scan below reads them in
    // sequence (most of its tests fail, so it is bound by the reads).
    for (auto& c : sorted_) c.resize(n);
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) sorted_[d][i] = lo[3 * s[i] + d], sorted_[3 + d][i] = hi[3 * s[i] + d];
    const double *lx = sorted_[0].data(), *ly = sorted_[1].data(), *lz = sorted_[2].data();
    const double *hx = sorted_[3].data(), *hy = sorted_[4].data(), *hz = sorted_[5].data();
    found_.clear();
    for (int i = 0; i < n; ++i) {
      const double ahx = hx[i], alx = lx[i], aly = ly[i], ahy = hy[i], alz = lz[i], ahz = hz[i];
      for (int j = i + 1; j < n; ++j) {
        if (lx[j] > ahx) break;  // sorted by low x: no later box reaches a's x range
        if (hx[j] >= alx && hy[j] >= aly && ly[j] <= ahy && hz[j] >= alz && lz[j] <= ahz)
          found_.emplace_back(std::min(s[i], s[j]), std::max(s[i], s[j]));
      }
    }
    // Sorted: a radix sort of two stable counting sorts, by the second box, then by the first.
    by_second_.resize(found_.size());
    counting_sort(found_, by_second_, n, [](const std::pair<int, int>& pq) { return pq.second; });
    counting_sort(by_second_, out, n, [](const std::pair<int, int>& pq) { return pq.first; });
  }

 private:
  // Stable: pairs with the same key keep their order in `in`.
  template <class Key>
  void counting_sort(const std::vector<std::pair<int, int>>& in, std::vector<std::pair<int, int>>& out, int n, Key key) {
    fill_.assign(n + 1, 0);
    for (const auto& pq : in) ++fill_[key(pq) + 1];
    for (int i = 0; i < n; ++i) fill_[i + 1] += fill_[i];
    out.resize(in.size());
    for (const auto& pq : in) out[fill_[key(pq)]++] = pq;
  }

  std::vector<int> order_, fill_;
  std::vector<double> sorted_[6];  // low x, y, z, high x, y, z in sweep order
  std::vector<std::pair<int, int>> found_, by_second_;
};

}  // namespace dcshell::unfold_detail
