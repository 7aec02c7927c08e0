// Private to the cut module: the objective g(n, d) of a CutProblem, evaluated through slice
// profiles (one build per direction) and differentiated through plane sections. An interference
// region that lies wholly on one side of every offset asked for adds a constant (all of its
// volume or none), so it gets no profile: where many hulls share a region, most of a pair's
// interference regions lie outside the slab its plane can move in.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "dcshell/fit_cut_plane.h"
#include "dcshell/slice_volume.h"

namespace dcshell {

class CutObjective {
 public:
  /// `problem` must carry its current overlap (with_current_overlap).
  CutObjective(const CutProblem& problem, double lambda);

  /// The best plane with unit normal n: offset minimising g within the overlap's range.
  struct Best {
    CutPlane plane;
    double value = 0.0;
  };
  Best best_offset(const Eigen::Vector3d& n);

  /// g at a given plane (normal normalised first).
  double value(const CutPlane& plane);

  /// Gradient of n -> min_d g(n, d) at its minimiser plane (from best_offset), with respect to
  /// an unnormalised normal: first moments of the sections, plus the motion of the range end
  /// when the offset sits on it.
  Eigen::Vector3d normal_gradient(const Best& best);

  /// Offset range along unit n through which the plane must pass.
  std::pair<double, double> range(const Eigen::Vector3d& n) const;

  /// vol(a ∩ H+) + vol(b ∩ H-) (no interference) at a plane.
  double separated_volume(const CutPlane& plane);

  const CutProblem& problem() const { return problem_; }
  /// Vertices of the overlap used for the range.
  const std::vector<Eigen::Vector3d>& range_points() const { return range_points_; }

 private:
  // Profiles along unit n valid for offsets in [lo, hi]: every term whose heights straddle the
  // interval gets one (the two hulls always), the others add their constant to constant_.
  void build(const Eigen::Vector3d& n, double lo, double hi);
  struct Term {
    const ConvexPolytope* poly;
    double weight;
    bool above;
    double volume;  // of poly, for a term that lies on one side of the offsets
  };
  const CutProblem& problem_;
  std::vector<Term> terms_;
  std::vector<SliceProfile> profiles_;
  std::vector<SliceTerm> slice_terms_;  // the terms with a profile in the last build
  double constant_ = 0.0;               // the others' sum there
  std::vector<Eigen::Vector3d> range_points_;
  Eigen::Vector3d built_ = Eigen::Vector3d::Zero();
  double built_lo_ = 0.0, built_hi_ = -1.0;  // the offsets the last build is valid for
};

}  // namespace dcshell
