// Stage "cut", slice volume: for a fixed unit direction c, the volume of P ∩ {c·x >= d} as an
// exact piecewise cubic in d. Between two consecutive vertex heights the section P ∩ {c·x = d}
// keeps its combinatorics, so its area is a quadratic in d and the volume its integral.
//
// Construction is a sweep over faces, O(V log V + E): each face contributes one edge of the
// section polygon, and that edge only changes when the plane passes a vertex of the face. Every
// such (face, height range) piece is added once to a difference array, except pieces using a
// nearly horizontal edge: those are accumulated interval by interval in local coordinates, so
// the steep (ill-conditioned) polynomials never enter a running sum. Vertices of any degree and
// directions orthogonal to edges or faces need no special case: equal heights simply merge.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "dcshell/convex_polytope.h"

namespace dcshell {

class SliceProfile {
 public:
  SliceProfile() = default;
  /// `direction` must be a unit vector; `p` a closed convex polytope with outward faces.
  SliceProfile(const ConvexPolytope& p, const Eigen::Vector3d& direction) { build(p, direction); }
  /// Rebuilds in place, reusing the storage (cheap to call once per direction in a sweep).
  void build(const ConvexPolytope& p, const Eigen::Vector3d& direction);

  const Eigen::Vector3d& direction() const { return dir_; }
  double volume() const { return below_.empty() ? 0.0 : below_.back(); }
  /// Lowest and highest vertex height c·v (min > max when the polytope is empty).
  double min_height() const { return h_.empty() ? 0.0 : h_.front() + shift_; }
  double max_height() const { return h_.empty() ? 0.0 : h_.back() + shift_; }

  /// vol(P ∩ {c·x >= d}) and vol(P ∩ {c·x <= d}).
  double volume_above(double d) const;
  double volume_below(double d) const;
  /// Area of P ∩ {c·x = d} (= -d/dd volume_above(d)).
  double area(double d) const;

  /// Pieces: the distinct vertex heights h_0 < ... < h_m; on [h_k, h_k+1] the section area is
  /// a0 + a1 s + a2 s^2 with s = (d - h_k) / (h_k+1 - h_k).
  std::size_t num_pieces() const { return coef_.size(); }
  double height(std::size_t k) const { return h_[k] + shift_; }
  const Eigen::Vector3d& piece(std::size_t k) const { return coef_[k]; }
  /// Index k of the piece containing d (clamped to [0, num_pieces()-1]); requires pieces.
  std::size_t piece_index(double d) const;
  /// The same index, searched from `hint` (an earlier answer): O(1) when d moves little, as in
  /// a sweep over increasing offsets.
  std::size_t piece_index(double d, std::size_t hint) const;
  /// volume_above / volume_below with a search hint, updated to the piece used (same values).
  double volume_above(double d, std::size_t& hint) const;
  double volume_below(double d, std::size_t& hint) const;

 private:
  Eigen::Vector3d dir_ = Eigen::Vector3d::UnitZ();
  double shift_ = 0.0;           // c·o for the centre o; heights are stored relative to it
  std::vector<double> h_;        // distinct heights, increasing
  std::vector<Eigen::Vector3d> coef_;
  std::vector<double> below_;    // below_[k] = vol(P ∩ {c·x <= h_k})
  std::vector<double> above_;    // above_[k] = vol(P ∩ {c·x >= h_k})
  double above_in(std::size_t k, double x) const;  // volume_above inside piece k, x = d - shift_
  double below_in(std::size_t k, double x) const;
  // scratch reused between builds
  std::vector<Eigen::Vector3d> q_;
  std::vector<double> hv_;
  std::vector<int> rank_, order_;
  std::vector<Eigen::Vector3d> diff_;
};

/// One term of an objective weight * vol(P ∩ side of the plane c·x = d).
struct SliceTerm {
  const SliceProfile* profile = nullptr;
  double weight = 1.0;
  bool above = true;  ///< true: counts P ∩ {c·x >= d}; false: P ∩ {c·x <= d}
};

/// Sum of the terms at offset d.
double slice_objective(const std::vector<SliceTerm>& terms, double d);
/// Its derivative in d (weighted section areas, signed by side).
double slice_objective_derivative(const std::vector<SliceTerm>& terms, double d);

struct OffsetMinimum {
  double offset = 0.0;
  double value = 0.0;
};

/// Global minimiser of the objective over d in [lo, hi] (all profiles share one direction).
/// Exact up to rounding: the derivative is a quadratic on each interval between the events of
/// all profiles, so the candidates are the interval ends and the roots of those quadratics.
/// O(total events) after the builds. Ties go to the smallest offset.
OffsetMinimum minimize_offset(const std::vector<SliceTerm>& terms, double lo, double hi);

}  // namespace dcshell
