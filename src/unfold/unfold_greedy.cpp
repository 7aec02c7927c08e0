// Overlap-aware greedy cut trees (the way Blender's "Export Paper Model" add-on builds islands,
// but always ending in one piece).
//
// Kruskal over the facet groups in a priority order: every facet starts as a piece laid out in
// its own chart; a group joining two pieces is folded when the two pieces, placed rigidly along
// it, do not overlap, and refused otherwise (the relative placement of two pieces along a group
// never changes, so a refused join stays refused while both pieces only grow). When only
// refused joins remain, the smallest piece is stuck (typically one facet enclosed by a larger
// piece): it and its neighbouring facets are cut free (the pieces around fall apart into parts
// that keep their placement), the freed facets are joined among themselves first, then the
// passes go on; a piece stuck again frees a wider neighbourhood. Past a budget (4x the facets
// freed in all), the smallest piece is joined through its least overlapping group. The result
// is always a spanning tree of the facet graph; the decoder and its overlap test judge the
// final net, the placement here is only the filter.
//
// Overlap test: the smaller piece's triangles, moved by the join's motion and shrunk by 1e-7
// relative (faces touching along the join meet only up to rounding), against the larger piece's
// through a uniform grid of the larger piece (cells the median triangle size), exact predicate
// on the doubles (triangle_interiors_overlap). The smaller piece is merged into the larger's
// frame, so every triangle moves O(log n) times.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "dcshell/net_overlap.h"
#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

namespace {

using Vec2 = Eigen::Vector2d;

struct Box2 {
  Vec2 lo, hi;
};
Box2 box_of(const Triangle2& t) {
  Box2 b{t[0], t[0]};
  for (int k = 1; k < 3; ++k) b.lo = b.lo.cwiseMin(t[k]), b.hi = b.hi.cwiseMax(t[k]);
  return b;
}
bool boxes_meet(const Box2& a, const Box2& b) {
  return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() && b.lo.y() <= a.hi.y();
}
Triangle2 shrunk(const Triangle2& t) {
  Vec2 c = (t[0] + t[1] + t[2]) / 3;
  Triangle2 s;
  for (int k = 0; k < 3; ++k) s[k] = c + (t[k] - c) * (1 - 1e-7);
  return s;
}

struct Aborted {};

class Greedy {
 public:
  Greedy(const ShellGraph& G, double work_limit) : G_(G), work_limit_(work_limit) {
    const int nf = static_cast<int>(G.F.size());
    const int nk = G.num_facets;
    pos_.resize(nf);
    for (int f = 0; f < nf; ++f) pos_[f] = G.chart[f];
    facet_faces_.resize(nk);
    for (int f = 0; f < nf; ++f) facet_faces_[G.facet[f]].push_back(f);
    ends_.resize(G.num_groups());
    facet_groups_.resize(nk);
    for (int gi = 0; gi < G.num_groups(); ++gi) {
      ends_[gi] = G.group_facets(gi);
      facet_groups_[ends_[gi][0]].push_back(gi);
      facet_groups_[ends_[gi][1]].push_back(gi);
    }
    // Grid cells: the median triangle extent (a triangle then spans a few cells).
    std::vector<double> ext(nf);
    for (int f = 0; f < nf; ++f) {
      Box2 b = box_of(pos_[f]);
      ext[f] = std::max(b.hi.x() - b.lo.x(), b.hi.y() - b.lo.y());
    }
    std::nth_element(ext.begin(), ext.begin() + nf / 2, ext.end());
    cell_ = std::max(ext[nf / 2], 1e-12 * G.scale);
    piece_of_.resize(nk);
    pieces_.resize(nk);
    for (int k = 0; k < nk; ++k) reset_piece(k);
    folded_.assign(G.num_groups(), 0);
    refused_.assign(G.num_groups(), 0);
  }

  /// Folded groups of the search graph for the priority order `order` (all groups).
  std::vector<char> run(const std::vector<int>& order) {
    int repair_budget = 4 * G_.num_facets + 16;  // facets freed by repairs, in total
    for (;;) {
      pass(order, nullptr);
      if (piece_count() == 1) break;
      int s = smallest_piece();
      // Repair: free the stuck piece and its neighbours (cut off the pieces around it; the rest
      // of those pieces stays where it is) and rebuild that neighbourhood first.
      std::vector<char> freed(G_.num_facets, 0);
      std::vector<int> free_list;
      for (int k : pieces_[s].facets) {
        if (!freed[k]) freed[k] = 1, free_list.push_back(k);
        for (int gi : facet_groups_[k])
          for (int e : ends_[gi])
            if (!freed[e]) freed[e] = 1, free_list.push_back(e);
      }
      if (static_cast<int>(free_list.size()) <= repair_budget) {
        repair_budget -= static_cast<int>(free_list.size());
        split(free_list);
        pass(order, &freed);
        continue;
      }
      // Forced: the smallest piece through its least overlapping join.
      int best = -1;
      long best_n = 0;
      for (int gi : order) {
        int a = piece_of_[ends_[gi][0]], b = piece_of_[ends_[gi][1]];
        if (a == b || (a != s && b != s)) continue;
        long n = overlaps(gi, best < 0 ? -1 : best_n);
        if (best < 0 || n < best_n) best = gi, best_n = n;
        if (best_n == 0) break;
      }
      join(best);
      ++forced_;
    }
    return folded_;
  }
  int forced() const { return forced_; }

 private:
  struct Piece {
    std::vector<int> facets, faces;
    std::unordered_map<std::uint64_t, std::vector<int>> grid;
    std::vector<int> large;  // faces spanning too many cells: checked by box
  };
  static constexpr long kMaxCells = 64;

  void charge(double w) {
    work_ += w;
    if (work_ > work_limit_) throw Aborted{};
  }

  std::uint64_t key(long i, long j) const {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
  }
  void cell_range(const Box2& b, long& i0, long& i1, long& j0, long& j1) const {
    i0 = static_cast<long>(std::floor(b.lo.x() / cell_)), i1 = static_cast<long>(std::floor(b.hi.x() / cell_));
    j0 = static_cast<long>(std::floor(b.lo.y() / cell_)), j1 = static_cast<long>(std::floor(b.hi.y() / cell_));
  }
  void insert(Piece& p, int f) {
    p.faces.push_back(f);
    long i0, i1, j0, j1;
    cell_range(box_of(pos_[f]), i0, i1, j0, j1);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMaxCells) {
      p.large.push_back(f);
      return;
    }
    for (long i = i0; i <= i1; ++i)
      for (long j = j0; j <= j1; ++j) p.grid[key(i, j)].push_back(f);
    charge(static_cast<double>((i1 - i0 + 1) * (j1 - j0 + 1)));
  }
  void reset_piece(int k) {
    piece_of_[k] = k;
    Piece& p = pieces_[k];
    p = Piece{};
    p.facets = {k};
    for (int f : facet_faces_[k]) {
      pos_[f] = G_.chart[f];
      insert(p, f);
    }
  }

  // Rigid motion of piece `mover` that lands its side of group gi on the other side.
  bool motion(int gi, int mover, Eigen::Matrix2d& R, Vec2& T) const {
    const auto& e = G_.edges[G_.group_edges[gi][0]];
    int fs = e.f0, fb = e.f1;
    if (piece_of_[G_.facet[fs]] != mover) std::swap(fs, fb);
    auto at = [&](int f, int v) {
      for (int k = 0; k < 3; ++k)
        if (G_.F[f][k] == v) return pos_[f][k];
      return Vec2(0, 0);
    };
    Vec2 s0 = at(fs, e.v0), ds = at(fs, e.v1) - s0, b0 = at(fb, e.v0), db = at(fb, e.v1) - b0;
    double c = ds.dot(db), s = ds.x() * db.y() - ds.y() * db.x(), n = std::hypot(c, s);
    if (!(n > 0)) return false;
    c /= n, s /= n;
    R << c, -s, s, c;
    T = b0 - R * s0;
    return true;
  }

  // Overlapping triangle pairs between the two pieces joined along gi (stops above `cap` when
  // cap >= 0: only "more than cap" matters then).
  long overlaps(int gi, long cap) {
    int a = piece_of_[ends_[gi][0]], b = piece_of_[ends_[gi][1]];
    int mover = pieces_[a].faces.size() <= pieces_[b].faces.size() ? a : b, fixed = mover == a ? b : a;
    Eigen::Matrix2d R;
    Vec2 T;
    if (!motion(gi, mover, R, T)) return std::numeric_limits<long>::max() / 2;
    const Piece& P = pieces_[fixed];
    long n = 0;
    ++stamp_;
    if (seen_.size() < pos_.size()) seen_.assign(pos_.size(), 0);
    auto test = [&](const Triangle2& t, const Box2& tb, int f) {
      if (seen_[f] == stamp_) return;
      seen_[f] = stamp_;
      charge(1);
      if (!boxes_meet(tb, box_of(pos_[f]))) return;
      charge(4);
      if (triangle_interiors_overlap(t, shrunk(pos_[f]))) ++n;
    };
    for (int f : pieces_[mover].faces) {
      Triangle2 t;
      for (int k = 0; k < 3; ++k) t[k] = R * pos_[f][k] + T;
      t = shrunk(t);
      Box2 tb = box_of(t);
      ++stamp_;
      long i0, i1, j0, j1;
      cell_range(tb, i0, i1, j0, j1);
      if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMaxCells) {
        for (int h : P.faces) test(t, tb, h);
      } else {
        for (long i = i0; i <= i1; ++i)
          for (long j = j0; j <= j1; ++j) {
            charge(1);
            auto it = P.grid.find(key(i, j));
            if (it != P.grid.end())
              for (int h : it->second) test(t, tb, h);
          }
        for (int h : P.large) test(t, tb, h);
      }
      if (cap >= 0 && n > cap) return n;
    }
    return n;
  }

  void join(int gi) {
    int a = piece_of_[ends_[gi][0]], b = piece_of_[ends_[gi][1]];
    int mover = pieces_[a].faces.size() <= pieces_[b].faces.size() ? a : b, fixed = mover == a ? b : a;
    Eigen::Matrix2d R;
    Vec2 T;
    if (!motion(gi, mover, R, T)) R.setIdentity(), T.setZero();  // degenerate: any placement
    Piece& P = pieces_[fixed];
    Piece M = std::move(pieces_[mover]);
    pieces_[mover] = Piece{};
    for (int f : M.faces) {
      for (auto& p : pos_[f]) p = R * p + T;
      insert(P, f);
    }
    for (int k : M.facets) piece_of_[k] = fixed, P.facets.push_back(k);
    folded_[gi] = 1;
  }

  // Cuts every folded group at the given facets; the pieces holding them fall apart into
  // their connected parts, which keep their placement (a part of a placed piece is placed).
  void split(const std::vector<int>& isolate) {
    std::vector<int> roots;
    for (int k : isolate) {
      roots.push_back(piece_of_[k]);
      for (int gi : facet_groups_[k]) folded_[gi] = 0;
    }
    std::sort(roots.begin(), roots.end());
    roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
    std::vector<char> mark(G_.num_facets, 0);
    for (int r : roots) {
      // Parts of piece r; the largest keeps r's grid (the others' faces leave it), so cutting a
      // few facets off a large piece costs the few facets, not the piece.
      std::vector<std::vector<int>> parts;
      for (int k : pieces_[r].facets)
        for (int gi : facet_groups_[k]) refused_[gi] = 0;
      for (int k0 : pieces_[r].facets) {
        if (mark[k0]) continue;
        std::vector<int> part, stack = {k0};
        mark[k0] = 1;
        while (!stack.empty()) {
          int k = stack.back();
          stack.pop_back();
          part.push_back(k);
          for (int gi : facet_groups_[k]) {
            if (!folded_[gi]) continue;
            int o = ends_[gi][0] == k ? ends_[gi][1] : ends_[gi][0];
            if (!mark[o]) mark[o] = 1, stack.push_back(o);
          }
        }
        parts.push_back(std::move(part));
      }
      std::size_t keep = 0;
      for (std::size_t i = 1; i < parts.size(); ++i)
        if (parts[i].size() > parts[keep].size()) keep = i;
      Piece big = std::move(pieces_[r]);
      pieces_[r] = Piece{};
      std::vector<char> leaving(pos_.size(), 0);
      for (std::size_t i = 0; i < parts.size(); ++i) {
        if (i == keep) continue;
        Piece p;
        for (int k : parts[i]) {
          p.facets.push_back(k);
          piece_of_[k] = parts[i][0];
          for (int f : facet_faces_[k]) {
            leaving[f] = 1;
            remove(big, f);
            insert(p, f);
          }
        }
        pieces_[parts[i][0]] = std::move(p);
      }
      auto gone = [&](int f) { return leaving[f] != 0; };
      big.faces.erase(std::remove_if(big.faces.begin(), big.faces.end(), gone), big.faces.end());
      big.large.erase(std::remove_if(big.large.begin(), big.large.end(), gone), big.large.end());
      big.facets = parts[keep];
      int root = parts[keep][0];
      for (int k : big.facets) piece_of_[k] = root;
      pieces_[root] = std::move(big);
    }
  }

  void remove(Piece& p, int f) {
    long i0, i1, j0, j1;
    cell_range(box_of(pos_[f]), i0, i1, j0, j1);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMaxCells) return;  // in p.large
    for (long i = i0; i <= i1; ++i)
      for (long j = j0; j <= j1; ++j) {
        auto it = p.grid.find(key(i, j));
        if (it == p.grid.end()) continue;
        auto& v = it->second;
        charge(static_cast<double>(v.size()));
        v.erase(std::remove(v.begin(), v.end(), f), v.end());
      }
  }

  int piece_count() const {
    int n = 0;
    for (int k = 0; k < G_.num_facets; ++k) n += piece_of_[k] == k;
    return n;
  }

  // One Kruskal pass; `freed`: only the groups between two freed facets.
  int pass(const std::vector<int>& order, const std::vector<char>* freed) {
    int joins = 0;
    for (int gi : order) {
      if (refused_[gi]) continue;
      int a = piece_of_[ends_[gi][0]], b = piece_of_[ends_[gi][1]];
      if (a == b) continue;
      if (freed && !((*freed)[ends_[gi][0]] && (*freed)[ends_[gi][1]])) continue;
      if (overlaps(gi, 0) == 0) {
        join(gi);
        ++joins;
      } else {
        refused_[gi] = 1;
      }
    }
    return joins;
  }

  int smallest_piece() const {
    int s = -1;
    for (int k = 0; k < G_.num_facets; ++k)
      if (piece_of_[k] == k && (s < 0 || pieces_[k].facets.size() < pieces_[s].facets.size())) s = k;
    return s;
  }

  const ShellGraph& G_;
  double work_limit_, work_ = 0;
  double cell_ = 1;
  std::vector<std::array<Vec2, 3>> pos_;
  std::vector<std::vector<int>> facet_faces_, facet_groups_;
  std::vector<std::array<int, 2>> ends_;
  std::vector<int> piece_of_;
  std::vector<Piece> pieces_;
  std::vector<char> folded_, refused_;
  std::vector<std::uint64_t> seen_;
  std::uint64_t stamp_ = 0;
  int forced_ = 0;
};

}  // namespace

Genome greedy_weights(const ShellGraph& g, const SearchGraph& sg, int variant, std::uint64_t seed) {
  const ShellGraph& G = sg.use_coarse ? sg.coarse : *sg.fine;
  const int ng = g.num_groups();
  if (G.num_groups() != ng || G.num_facets < 1) return {};
  std::vector<int> to_fine(ng);
  for (int gi = 0; gi < ng; ++gi) to_fine[sg.use_coarse ? sg.group_map[gi] : gi] = gi;

  // Priority keys per fine group (lower folds first).
  double mean_len = 0;
  for (double l : g.group_length) mean_len += l;
  mean_len = std::max(mean_len / std::max(ng, 1), 1e-300);
  Rng rng(mix_seed(seed, 0x67726565ULL, static_cast<std::uint64_t>(variant)));
  std::vector<double> key(ng);
  for (int gi = 0; gi < ng; ++gi) {
    double len = g.group_length[gi] / mean_len;
    double angle = std::abs(g.edges[g.group_edges[gi][0]].fold_angle) / M_PI;
    if (g.edges[g.group_edges[gi][0]].fold_angle < 0) angle *= 2;  // reflex: Blender's concave 1 vs convex 0.5
    switch (variant) {
      case 0: key[gi] = -len; break;                             // longest fold first
      case 1: key[gi] = 0.5 * angle - 0.05 * len; break;         // Blender's default priority
      case 2: key[gi] = 0.5 * angle - 0.5 * len; break;          // angle and length alike
      default: key[gi] = -len * (1 + 0.05 * (variant - 2) * (rng.uniform() - 0.5)); break;  // jittered
    }
  }
  std::vector<int> order(ng);  // search-graph groups
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[to_fine[a]] < key[to_fine[b]]; });

  // Work: a few hundred triangle tests per face; beyond that the shell is left to the others.
  const double limit = 2e7 + 400.0 * static_cast<double>(G.F.size());
  std::vector<char> folded;
  try {
    Greedy greedy(G, limit);
    folded = greedy.run(order);
  } catch (const Aborted&) {
    return {};
  }
  Genome w(ng);
  for (int sgi = 0; sgi < ng; ++sgi) w[to_fine[sgi]] = folded[sgi] ? 0.0 : 1.0;
  return w;
}

}  // namespace dcshell::unfold_detail
