// Exact piecewise-cubic slice volume of a convex polytope along a direction.
#include "dcshell/slice_volume.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dcshell {

namespace {

// Edges whose length exceeds kSteep times their height difference are "nearly horizontal":
// their crossing point moves fast, so their polynomial in the global offset has large
// coefficients. Those pieces are accumulated locally (see the header). A global polynomial of
// slope k loses about k^2 ulps of the section area: 64 keeps that near 1e-12 while the local
// (per-interval, slower) path stays rare.
constexpr double kSteep = 64.0;

inline double det3(const Eigen::Vector3d& c, const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return c.dot(x.cross(y));
}

// Real roots of a2 s^2 + a1 s + a0 in the open interval (0, 1).
template <class Out>
void roots_in_unit(double a2, double a1, double a0, Out out) {
  const double scale = std::max({std::fabs(a0), std::fabs(a1), std::fabs(a2)});
  if (!(scale > 0)) return;
  auto emit = [&](double r) {
    if (r > 0 && r < 1) out(r);
  };
  if (std::fabs(a2) <= 1e-12 * scale) {
    if (std::fabs(a1) > 1e-12 * scale) emit(-a0 / a1);
    return;
  }
  const double disc = a1 * a1 - 4 * a2 * a0;
  if (disc < 0) return;
  // Numerically stable pair of roots.
  const double q = -0.5 * (a1 + std::copysign(std::sqrt(disc), a1));
  emit(q / a2);
  if (q != 0) emit(a0 / q);
}

}  // namespace

void SliceProfile::build(const ConvexPolytope& p, const Eigen::Vector3d& c) {
  dir_ = c;
  h_.clear();
  coef_.clear();
  below_.clear();
  above_.clear();
  if (p.empty()) return;
  const std::size_t nv = p.vertices.size();
  // Centre the polytope: all later terms are then of the size of the polytope itself.
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  for (const auto& v : p.vertices) o += v;
  o /= double(nv);
  shift_ = c.dot(o);
  q_.resize(nv);
  hv_.resize(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    q_[i] = p.vertices[i] - o;
    hv_[i] = c.dot(q_[i]);
  }
  order_.resize(nv);
  std::iota(order_.begin(), order_.end(), 0);
  std::sort(order_.begin(), order_.end(), [&](int a, int b) { return hv_[a] < hv_[b] || (hv_[a] == hv_[b] && a < b); });
  rank_.resize(nv);
  for (int i : order_) {
    if (h_.empty() || hv_[i] != h_.back()) h_.push_back(hv_[i]);
    rank_[i] = int(h_.size()) - 1;
  }
  const std::size_t m = h_.size();
  if (m < 2) {  // flat: no volume
    h_.clear();
    return;
  }
  diff_.assign(m, Eigen::Vector3d::Zero());
  coef_.assign(m - 1, Eigen::Vector3d::Zero());

  // One piece of the section polygon: the segment between the crossings of the "down" edge
  // (loop goes from above to below) and the "up" edge, over intervals [ra, rb).
  auto add_piece = [&](int du, int dw, int uu, int uw, int ra, int rb) {
    const Eigen::Vector3d ed = q_[dw] - q_[du], eu = q_[uw] - q_[uu];
    const double dhd = hv_[dw] - hv_[du], dhu = hv_[uw] - hv_[uu];
    const bool steep = ed.squaredNorm() > kSteep * kSteep * dhd * dhd ||
                       eu.squaredNorm() > kSteep * kSteep * dhu * dhu;
    if (!steep) {
      // Crossing points as A + d B in the (local) offset d.
      const Eigen::Vector3d Bd = ed / dhd, Bu = eu / dhu;
      const Eigen::Vector3d Ad = q_[du] - hv_[du] * Bd, Au = q_[uu] - hv_[uu] * Bu;
      const Eigen::Vector3d t(det3(c, Ad, Au), det3(c, Ad, Bu) + det3(c, Bd, Au), det3(c, Bd, Bu));
      diff_[ra] += 0.5 * t;
      diff_[rb] -= 0.5 * t;
      return;
    }
    for (int k = ra; k < rb; ++k) {
      const double w = h_[k + 1] - h_[k];
      const Eigen::Vector3d D0 = q_[du] + ((h_[k] - hv_[du]) / dhd) * ed, D1 = (w / dhd) * ed;
      const Eigen::Vector3d U0 = q_[uu] + ((h_[k] - hv_[uu]) / dhu) * eu, U1 = (w / dhu) * eu;
      coef_[k] += 0.5 * Eigen::Vector3d(det3(c, D0, U0), det3(c, D0, U1) + det3(c, D1, U0), det3(c, D1, U1));
    }
  };

  std::vector<int> fr;  // distinct ranks of a face
  for (const auto& f : p.faces) {
    const std::size_t L = f.size();
    if (L == 3) {  // fast path (hulls are triangulated): lowest l, middle m, highest h
      int l = 0, m = 1, h = 2;
      if (rank_[f[m]] < rank_[f[l]]) std::swap(l, m);
      if (rank_[f[h]] < rank_[f[m]]) std::swap(m, h);
      if (rank_[f[m]] < rank_[f[l]]) std::swap(l, m);
      const int rl = rank_[f[l]], rm = rank_[f[m]], rh = rank_[f[h]];
      if (rl == rh) continue;
      // The long edge l-h crosses throughout; in loop order it goes up when h follows l.
      const bool lh_up = h == (l + 1) % 3;
      auto piece = [&](int x, int y, int ra, int rb) {  // short edge x (lower) - y (upper)
        if (lh_up) add_piece(f[y], f[x], f[l], f[h], ra, rb);
        else add_piece(f[h], f[l], f[x], f[y], ra, rb);
      };
      if (rl < rm) piece(l, m, rl, rm);
      if (rm < rh) piece(m, h, rm, rh);
      continue;
    }
    fr.clear();
    for (int v : f) fr.push_back(rank_[v]);
    std::sort(fr.begin(), fr.end());
    fr.erase(std::unique(fr.begin(), fr.end()), fr.end());
    for (std::size_t j = 0; j + 1 < fr.size(); ++j) {
      const int ra = fr[j], rb = fr[j + 1];
      int up = -1, down = -1;
      for (std::size_t i = 0; i < L; ++i) {
        const int r0 = rank_[f[i]], r1 = rank_[f[(i + 1) % L]];
        if (r0 <= ra && r1 >= rb) up = int(i);
        if (r0 >= rb && r1 <= ra) down = int(i);
      }
      if (up < 0 || down < 0) continue;  // non-convex face (cannot happen for valid input)
      add_piece(f[down], f[(down + 1) % L], f[up], f[(up + 1) % L], ra, rb);
    }
  }

  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  below_.assign(m, 0.0);
  above_.assign(m, 0.0);
  for (std::size_t k = 0; k + 1 < m; ++k) {
    g += diff_[k];
    const double hk = h_[k], w = h_[k + 1] - h_[k];
    coef_[k] += Eigen::Vector3d(g[0] + hk * (g[1] + hk * g[2]), (g[1] + 2 * g[2] * hk) * w, g[2] * w * w);
    const double vk = w * (coef_[k][0] + coef_[k][1] / 2 + coef_[k][2] / 3);
    below_[k + 1] = below_[k] + vk;
  }
  for (std::size_t k = m - 1; k-- > 0;) {
    const double w = h_[k + 1] - h_[k];
    above_[k] = above_[k + 1] + w * (coef_[k][0] + coef_[k][1] / 2 + coef_[k][2] / 3);
  }
  if (below_.back() < 0) {  // inward-oriented faces: flip the signs rather than fail
    for (auto& a : coef_) a = -a;
    for (auto& v : below_) v = -v;
    for (auto& v : above_) v = -v;
  }
}

std::size_t SliceProfile::piece_index(double d) const {
  const double x = d - shift_;
  const std::size_t k = std::upper_bound(h_.begin(), h_.end(), x) - h_.begin();
  return std::min(k == 0 ? 0 : k - 1, coef_.size() - 1);
}

std::size_t SliceProfile::piece_index(double d, std::size_t hint) const {
  // The last k with h_k <= x, clamped to the pieces: what the binary search above returns.
  const double x = d - shift_;
  const std::size_t last = coef_.size() - 1;
  std::size_t k = std::min(hint, last);
  while (k > 0 && h_[k] > x) --k;
  while (k < last && h_[k + 1] <= x) ++k;
  return k;
}

double SliceProfile::above_in(std::size_t k, double x) const {
  const double w = h_[k + 1] - h_[k], s = (x - h_[k]) / w;
  const auto& a = coef_[k];
  return above_[k + 1] + w * (a[0] * (1 - s) + a[1] * (1 - s * s) / 2 + a[2] * (1 - s * s * s) / 3);
}

double SliceProfile::below_in(std::size_t k, double x) const {
  const double w = h_[k + 1] - h_[k], s = (x - h_[k]) / w;
  const auto& a = coef_[k];
  return below_[k] + w * s * (a[0] + s * (a[1] / 2 + s * a[2] / 3));
}

double SliceProfile::volume_above(double d) const {
  if (coef_.empty()) return 0.0;
  const double x = d - shift_;
  if (x <= h_.front()) return above_.front();
  if (x >= h_.back()) return 0.0;
  return above_in(piece_index(d), x);
}

double SliceProfile::volume_below(double d) const {
  if (coef_.empty()) return 0.0;
  const double x = d - shift_;
  if (x <= h_.front()) return 0.0;
  if (x >= h_.back()) return below_.back();
  return below_in(piece_index(d), x);
}

double SliceProfile::volume_above(double d, std::size_t& hint) const {
  if (coef_.empty()) return 0.0;
  const double x = d - shift_;
  if (x <= h_.front()) return above_.front();
  if (x >= h_.back()) return 0.0;
  return above_in(hint = piece_index(d, hint), x);
}

double SliceProfile::volume_below(double d, std::size_t& hint) const {
  if (coef_.empty()) return 0.0;
  const double x = d - shift_;
  if (x <= h_.front()) return 0.0;
  if (x >= h_.back()) return below_.back();
  return below_in(hint = piece_index(d, hint), x);
}

double SliceProfile::area(double d) const {
  if (coef_.empty()) return 0.0;
  const double x = d - shift_;
  if (x < h_.front() || x > h_.back()) return 0.0;
  const std::size_t k = piece_index(d);
  const double s = (x - h_[k]) / (h_[k + 1] - h_[k]);
  const auto& a = coef_[k];
  return a[0] + s * (a[1] + s * a[2]);
}

double slice_objective(const std::vector<SliceTerm>& terms, double d) {
  double v = 0.0;
  for (const auto& t : terms) v += t.weight * (t.above ? t.profile->volume_above(d) : t.profile->volume_below(d));
  return v;
}

double slice_objective_derivative(const std::vector<SliceTerm>& terms, double d) {
  double v = 0.0;
  for (const auto& t : terms) v += (t.above ? -t.weight : t.weight) * t.profile->area(d);
  return v;
}

OffsetMinimum minimize_offset(const std::vector<SliceTerm>& terms, double lo, double hi) {
  if (hi < lo) std::swap(lo, hi);
  std::vector<double> xs{lo, hi};
  for (const auto& t : terms)
    for (std::size_t k = 0; k <= t.profile->num_pieces() && t.profile->num_pieces() > 0; ++k) {
      const double h = t.profile->height(k);
      if (h > lo && h < hi) xs.push_back(h);
    }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());

  // The candidates come in increasing order (but for the roots inside one interval), so each
  // term's piece is found from its previous one: the same pieces, hence the same sums, as
  // slice_objective, without a binary search per term and candidate.
  std::vector<std::size_t> hint(terms.size(), 0);
  for (std::size_t i = 0; i < terms.size(); ++i)
    if (terms[i].profile->num_pieces() > 0) hint[i] = terms[i].profile->piece_index(lo);
  auto objective = [&](double d) {
    double v = 0.0;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const SliceTerm& t = terms[i];
      v += t.weight * (t.above ? t.profile->volume_above(d, hint[i]) : t.profile->volume_below(d, hint[i]));
    }
    return v;
  };
  OffsetMinimum best{lo, objective(lo)};
  auto consider = [&](double d) {
    const double v = objective(d);
    if (v < best.value || (v == best.value && d < best.offset)) best = {d, v};
  };
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    const double x0 = xs[i], x1 = xs[i + 1], mid = 0.5 * (x0 + x1);
    // Derivative on [x0, x1] as a quadratic in sigma = (d - x0) / (x1 - x0).
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (std::size_t j = 0; j < terms.size(); ++j) {
      const SliceTerm& t = terms[j];
      const SliceProfile& p = *t.profile;
      if (p.num_pieces() == 0 || mid <= p.min_height() || mid >= p.max_height()) continue;
      const std::size_t k = hint[j] = p.piece_index(mid, hint[j]);
      const double hk = p.height(k), w = p.height(k + 1) - hk;
      const double al = (x0 - hk) / w, be = (x1 - x0) / w;
      const auto& a = p.piece(k);
      const Eigen::Vector3d b(a[0] + al * (a[1] + al * a[2]), be * (a[1] + 2 * al * a[2]), a[2] * be * be);
      q += (t.above ? -t.weight : t.weight) * b;
    }
    roots_in_unit(q[2], q[1], q[0], [&](double s) { consider(x0 + s * (x1 - x0)); });
    consider(x1);
  }
  return best;
}

}  // namespace dcshell
