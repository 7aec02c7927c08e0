// Pair slots of the folding check (fold_check.cpp) for nets too large for a dense p x q table:
// per piece, its partners' slots sorted by partner. The step loop looks up every candidate pair
// in every step, in (p, q) order (BoxSweep's output), so consecutive lookups read the same short
// array; std::unordered_map's node per entry made each lookup a cache miss (a fifth of the check
// of a 3,500-piece net).
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace dcshell::unfold_detail {

class PairSlots {
 public:
  /// Pieces are 0 .. pieces - 1; growing keeps the slots already made.
  void resize(std::size_t pieces) {
    if (by_piece_.size() < pieces) by_piece_.resize(pieces);
  }
  /// The slot of pair (p, q), -1 when new. Valid until the next insertion.
  int& operator()(int p, int q) {
    auto& row = by_piece_[p];
    auto it = std::lower_bound(row.begin(), row.end(), q, [](const Cell& c, int k) { return c.partner < k; });
    if (it == row.end() || it->partner != q) it = row.insert(it, Cell{q, -1});
    return it->value;
  }

 private:
  struct Cell {
    int partner;
    int value;
  };
  std::vector<std::vector<Cell>> by_piece_;
};

}  // namespace dcshell::unfold_detail
