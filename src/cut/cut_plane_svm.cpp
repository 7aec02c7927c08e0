// Point sampling in convex polytopes and a linear SVM by dual coordinate descent.
#include "dcshell/cut_plane_svm.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "dcshell/polytope_clip.h"

namespace dcshell {

namespace {

// Uniform double in [0, 1) from the top 53 bits: std::uniform_real_distribution is
// implementation-defined, this is not.
double uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

// Index in [0, n) without std::uniform_int_distribution (also implementation-defined).
std::size_t uniform_index(std::mt19937_64& rng, std::size_t n) {
  return std::min<std::size_t>(std::size_t(uniform01(rng) * double(n)), n - 1);
}

}  // namespace

namespace {

bool lex_less(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
}

}  // namespace

std::vector<Eigen::Vector3d> sample_polytope(const ConvexPolytope& p, std::size_t count, std::mt19937_64& rng) {
  std::vector<Eigen::Vector3d> out;
  if (p.empty() || count == 0) return out;
  // The samples must not depend on the order of vertices and faces (hull codes may order them
  // by memory address): sum the centre in sorted order and sort the fan triangles, each
  // rotated to start at its smallest vertex.
  std::vector<Eigen::Vector3d> sorted = p.vertices;
  std::sort(sorted.begin(), sorted.end(), lex_less);
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (const auto& v : sorted) r += v;
  r /= double(sorted.size());
  struct Tri { std::array<Eigen::Vector3d, 3> v; };
  std::vector<Tri> tris;
  for (const auto& f : p.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      Tri t{{p.vertices[f[0]], p.vertices[f[i]], p.vertices[f[i + 1]]}};
      const int k = lex_less(t.v[1], t.v[0]) ? (lex_less(t.v[2], t.v[1]) ? 2 : 1) : (lex_less(t.v[2], t.v[0]) ? 2 : 0);
      std::rotate(t.v.begin(), t.v.begin() + k, t.v.end());
      tris.push_back(t);
    }
  std::sort(tris.begin(), tris.end(), [](const Tri& x, const Tri& y) {
    for (int k = 0; k < 3; ++k) {
      if (lex_less(x.v[k], y.v[k])) return true;
      if (lex_less(y.v[k], x.v[k])) return false;
    }
    return false;
  });
  std::vector<const Tri*> tets;
  std::vector<double> cdf;
  double total = 0.0;
  for (const auto& t : tris) {
    const double v = std::fabs((t.v[0] - r).dot((t.v[1] - r).cross(t.v[2] - r)));
    if (!(v > 0)) continue;
    total += v;
    tets.push_back(&t);
    cdf.push_back(total);
  }
  if (tets.empty()) return out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t t = std::min<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), uniform01(rng) * total) - cdf.begin(),
                                                tets.size() - 1);
    // Uniform barycentric coordinates in a tetrahedron by folding the unit cube
    // (Rocchini & Cignoni 2000).
    double s = uniform01(rng), u = uniform01(rng), w = uniform01(rng);
    if (s + u > 1) s = 1 - s, u = 1 - u;
    if (u + w > 1) {
      const double tmp = w;
      w = 1 - s - u;
      u = 1 - tmp;
    } else if (s + u + w > 1) {
      const double tmp = w;
      w = s + u + w - 1;
      s = 1 - u - tmp;
    }
    const Tri& q = *tets[t];
    out.push_back((1 - s - u - w) * r + s * q.v[0] + u * q.v[1] + w * q.v[2]);
  }
  return out;
}

CutPlane linear_svm(const std::vector<Eigen::Vector3d>& negative, const std::vector<Eigen::Vector3d>& positive,
                    double c, std::uint64_t seed) {
  const std::size_t n = negative.size() + positive.size();
  Eigen::Vector3d mn = Eigen::Vector3d::Zero(), mp = Eigen::Vector3d::Zero();
  for (const auto& x : negative) mn += x;
  for (const auto& x : positive) mp += x;
  if (negative.empty() || positive.empty()) return {};
  mn /= double(negative.size());
  mp /= double(positive.size());
  // Normalise: centre between the class means, unit RMS radius, so c does not depend on units.
  const Eigen::Vector3d centre = 0.5 * (mn + mp);
  double rms = 0.0;
  for (const auto& x : negative) rms += (x - centre).squaredNorm();
  for (const auto& x : positive) rms += (x - centre).squaredNorm();
  rms = std::sqrt(rms / double(n));
  if (!(rms > 0)) rms = 1.0;
  Eigen::Matrix<double, 4, Eigen::Dynamic> X(4, n);  // augmented with 1: the bias
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool pos = i >= negative.size();
    const Eigen::Vector3d& x = pos ? positive[i - negative.size()] : negative[i];
    X.col(i) << (x - centre) / rms, 1.0;
    y[i] = pos ? 1.0 : -1.0;
  }
  // Dual coordinate descent for the L1-loss SVM (Hsieh et al. 2008):
  // min_a 1/2 a'Qa - 1'a, 0 <= a_i <= c, w = sum a_i y_i x_i.
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd qd = X.colwise().squaredNorm().transpose();
  Eigen::Vector4d w = Eigen::Vector4d::Zero();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  // Stopping rule as LIBLINEAR's dual solvers (projected-gradient spread); a cut plane does
  // not need more: the exact offset is optimised afterwards (and solving to 1e-4 moved the
  // normal by well under a degree on the two-bar study).
  for (int pass = 0; pass < 100; ++pass) {
    for (std::size_t i = n; i > 1; --i) std::swap(order[i - 1], order[uniform_index(rng, i)]);
    double pg_max = -std::numeric_limits<double>::infinity(), pg_min = -pg_max;
    for (std::size_t i : order) {
      const double g = y[i] * w.dot(X.col(i)) - 1.0;
      double pg = g;
      if (alpha[i] == 0) pg = std::min(g, 0.0);
      else if (alpha[i] == c) pg = std::max(g, 0.0);
      pg_max = std::max(pg_max, pg);
      pg_min = std::min(pg_min, pg);
      if (pg != 0) {
        const double old = alpha[i];
        alpha[i] = std::min(std::max(old - g / qd[i], 0.0), c);
        w += (alpha[i] - old) * y[i] * X.col(i);
      }
    }
    if (pg_max - pg_min < 1e-2) break;
  }
  Eigen::Vector3d normal = w.head<3>();
  const double len = normal.norm();
  if (!(len > 0)) {  // degenerate (identical classes): fall back to the means' axis
    normal = mp - mn;
    if (!(normal.norm() > 0)) normal = Eigen::Vector3d::UnitX();
    normal.normalize();
    return {normal, normal.dot(centre)};
  }
  // In normalised coordinates w·z + w3 = 0 with z = (x - centre)/rms.
  normal /= len;
  return {normal, normal.dot(centre) - w[3] * rms / len};
}

CutPlane svm_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b, double c, std::size_t samples,
                       std::uint64_t seed, std::optional<double> overlap_volume) {
  // Points of the overlap a ∩ b are samples of both classes: no plane can separate them, they
  // only add noise (on the two-bar study the normal spread by up to 20 degrees between seeds,
  // and more samples did not help). The classes are therefore a \ b and b \ a, drawn by
  // rejection, with counts proportional to their volumes; when one of them is (nearly) empty,
  // a nested pair, the whole hulls are used.
  std::vector<CutPlane> planes_a, planes_b;
  for (std::size_t f = 0; f < a.faces.size(); ++f) planes_a.push_back(face_plane(a, f));
  for (std::size_t f = 0; f < b.faces.size(); ++f) planes_b.push_back(face_plane(b, f));
  const auto inside = [](const std::vector<CutPlane>& planes, const Eigen::Vector3d& x) {
    for (const auto& h : planes)
      if (h.normal.dot(x) > h.offset) return false;
    return true;
  };
  const double va = volume(a), vb = volume(b), vab = overlap_volume ? *overlap_volume : volume(intersect(a, b));
  constexpr std::size_t kMin = 16;
  const bool exclusive = va - vab > 0.01 * va && vb - vab > 0.01 * vb;
  const double wa = exclusive ? va - vab : va, wb = exclusive ? vb - vab : vb;
  std::size_t na = kMin, nb = kMin;
  if (wa + wb > 0 && samples > 2 * kMin) {
    na = std::max(kMin, std::size_t(std::llround(double(samples) * wa / (wa + wb))));
    nb = std::max(kMin, samples > na ? samples - na : kMin);
  }
  std::mt19937_64 rng(seed);
  const auto draw = [&](const ConvexPolytope& p, const std::vector<CutPlane>& other, std::size_t count) {
    if (!exclusive) return sample_polytope(p, count, rng);
    std::vector<Eigen::Vector3d> kept;
    // The exclusive part has >= 1% of the volume: 200 rounds of `count` draws suffice.
    for (int round = 0; round < 200 && kept.size() < count; ++round)
      for (const auto& x : sample_polytope(p, count, rng))
        if (kept.size() < count && !inside(other, x)) kept.push_back(x);
    return kept;
  };
  const auto pa = draw(a, planes_b, na);
  const auto pb = draw(b, planes_a, nb);
  if (pa.empty() || pb.empty()) {
    Eigen::Vector3d n = centroid(b) - centroid(a);
    if (!(n.norm() > 0)) n = Eigen::Vector3d::UnitX();
    n.normalize();
    return {n, n.dot(0.5 * (centroid(a) + centroid(b)))};
  }
  return linear_svm(pa, pb, c, seed ^ 0x9e3779b97f4a7c15ULL);
}

}  // namespace dcshell
