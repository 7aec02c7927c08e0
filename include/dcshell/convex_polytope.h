// Double-precision convex polytope (boundary representation): the fast path used by the
// cut-plane optimisers. Nothing certified is decided here; the exact counterpart is
// ExactPolytope (exact_polytope.h).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "dcshell/cut_plane.h"

namespace dcshell {

struct ConvexPolytope {
  std::vector<Eigen::Vector3d> vertices;
  /// Faces as vertex loops, counter-clockwise seen from outside.
  std::vector<std::vector<int>> faces;
  /// Per face, a caller-defined tag telling where its plane came from (e.g. 0 = hull of the
  /// first part, 1 = hull of the second, >= 2 = a cut plane). Same size as faces (may be empty).
  std::vector<int> face_tags;

  bool empty() const { return faces.size() < 4; }
};

}  // namespace dcshell
