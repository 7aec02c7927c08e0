// Continuous folding check: every fold angle goes linearly from 0 (the flat net) to its shell
// angle (a straight line in configuration space, t in [0, 1]); is the motion free of
// self-intersection?
//
// Faces that share no shell vertex are checked conservatively: from time t the step dt is
// bounded so that no point can travel farther than the current separation of any candidate
// pair (speed of a point <= sum over the folds above its face of |angle| x distance to the fold
// axis). Candidate pairs come from CGAL::box_self_intersection_d on boxes inflated by that
// travel bound. Faces that share a shell vertex touch by design; they are checked at every step
// (sampled, not continuous) for contact away from the shared vertices and edge.
// Faces joined by flat folds move as one rigid piece and are never tested against each other.
#pragma once
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "dcshell/net.h"

namespace dcshell {

struct FoldCheckOptions {
  /// Smallest step; a pair closer than this allows is reported as a contact (not verified).
  double min_step = 1e-7;
  int max_steps = 5000;
};

struct FoldCheckResult {
  bool verified = false;  ///< the whole path t in [0, 1] is free of self-intersection
  int steps = 0;
  double t = 1;               ///< where the check stopped (1 when verified)
  int face_a = -1, face_b = -1;  ///< the colliding (or too close) faces when not verified
  std::string message;        ///< why not verified; empty when verified
};

FoldCheckResult check_folding(const Net& net, const FoldCheckOptions& options = {});

/// Net faces moved to folding state t (0 = flat net at z = 0, 1 = folded shell, in net
/// coordinates): corners of each face, in shell order.
std::vector<std::array<Eigen::Vector3d, 3>> folded_faces(const Net& net, double t);

}  // namespace dcshell
