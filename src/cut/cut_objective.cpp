#include "cut/cut_objective.h"

#include <cmath>
#include <limits>

#include "dcshell/polytope_clip.h"

namespace dcshell {

CutObjective::CutObjective(const CutProblem& pb, double lambda) : problem_(pb) {
  terms_.push_back({&pb.a, 1.0, true, 0.0});
  terms_.push_back({&pb.b, 1.0, false, 0.0});
  if (lambda != 0) {
    for (const auto& x : pb.interference_a)
      if (!x.empty()) terms_.push_back({&x, lambda, true, volume(x)});
    for (const auto& y : pb.interference_b)
      if (!y.empty()) terms_.push_back({&y, lambda, false, volume(y)});
  }
  profiles_.resize(terms_.size());
  slice_terms_.reserve(terms_.size());
  if (!pb.overlap.empty()) {
    range_points_ = pb.overlap.vertices;
  } else {
    const ConvexPolytope& ab = pb.current_overlap.value();  // with_current_overlap: every entry point
    if (!ab.empty()) {
      range_points_ = ab.vertices;
    } else {  // disjoint: any plane between (or through) the two is acceptable
      range_points_ = pb.a.vertices;
      range_points_.insert(range_points_.end(), pb.b.vertices.begin(), pb.b.vertices.end());
    }
  }
}

void CutObjective::build(const Eigen::Vector3d& n, double lo, double hi) {
  if (n == built_ && built_lo_ <= lo && hi <= built_hi_) return;
  slice_terms_.clear();
  constant_ = 0.0;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const Term& t = terms_[i];
    if (i >= 2) {  // interference: a constant unless it straddles the offsets
      double h_min = std::numeric_limits<double>::infinity(), h_max = -h_min;
      for (const auto& v : t.poly->vertices) {
        const double h = n.dot(v);
        h_min = std::min(h_min, h);
        h_max = std::max(h_max, h);
      }
      if (h_min >= hi || h_max <= lo) {
        // Wholly above every offset (h_min >= hi) or wholly below (h_max <= lo).
        if ((h_min >= hi) == t.above) constant_ += t.weight * t.volume;
        continue;
      }
    }
    profiles_[i].build(*t.poly, n);
    slice_terms_.push_back({&profiles_[i], t.weight, t.above});
  }
  built_ = n;
  built_lo_ = lo;
  built_hi_ = hi;
}

std::pair<double, double> CutObjective::range(const Eigen::Vector3d& n) const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& v : range_points_) {
    const double h = n.dot(v);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  if (!(lo <= hi)) lo = hi = 0.0;
  return {lo, hi};
}

namespace {
// Unit vector, returned unchanged when it already has unit length, so re-evaluating a
// method's plane reproduces its value bit for bit.
Eigen::Vector3d unit(const Eigen::Vector3d& n) { return n.squaredNorm() == 1.0 ? n : n.normalized(); }
}  // namespace

CutObjective::Best CutObjective::best_offset(const Eigen::Vector3d& n_in) {
  const Eigen::Vector3d n = unit(n_in);
  const auto [lo, hi] = range(n);
  build(n, lo, hi);
  const OffsetMinimum m = minimize_offset(slice_terms_, lo, hi);
  return {{n, m.offset}, m.value + constant_};
}

double CutObjective::value(const CutPlane& plane) {
  const double len = plane.normal.squaredNorm() == 1.0 ? 1.0 : plane.normal.norm();
  const double d = plane.offset / len;
  build(plane.normal / len, d, d);
  return slice_objective(slice_terms_, d) + constant_;
}

double CutObjective::separated_volume(const CutPlane& plane) {
  const double len = plane.normal.squaredNorm() == 1.0 ? 1.0 : plane.normal.norm();
  const double d = plane.offset / len;
  build(plane.normal / len, d, d);
  return profiles_[0].volume_above(d) + profiles_[1].volume_below(d);
}

Eigen::Vector3d CutObjective::normal_gradient(const Best& best) {
  // d/dn vol(P ∩ {n·x >= d}) = first moment of the section (for a unit n).
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double dd = 0.0;  // dg/dd
  for (const auto& t : terms_) {
    const PlaneSection s = section(*t.poly, best.plane);
    g += (t.above ? t.weight : -t.weight) * s.moment;
    dd += (t.above ? -t.weight : t.weight) * s.area;
  }
  // When the offset sits at an end of the range, it moves with the extreme vertex.
  const auto [lo, hi] = range(best.plane.normal);
  const double d = best.plane.offset;
  if (d <= lo || d >= hi) {
    const bool at_lo = d <= lo;
    const Eigen::Vector3d* ext = nullptr;
    double ext_h = 0.0;
    for (const auto& v : range_points_) {
      const double h = best.plane.normal.dot(v);
      if (!ext || (at_lo ? h < ext_h : h > ext_h)) ext = &v, ext_h = h;
    }
    if (ext) g += dd * *ext;
  }
  return g;
}

}  // namespace dcshell
