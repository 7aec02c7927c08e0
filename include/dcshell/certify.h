// Stage "certify": exact certification that meshes are closed convex polyhedra and pairwise
// interior-disjoint (sharing faces, edges or points is allowed). Decided with exact arithmetic
// on the coordinates exactly as given (doubles), so a file certified here is certified as written.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "dcshell/kernel.h"

namespace dcshell {

struct ConvexityVerdict {
  bool closed = false;   ///< closed, oriented, connected 2-manifold of sphere topology
  bool convex = false;   ///< every face plane has all vertices on its inner side (exact)
  bool outward = false;  ///< faces oriented outward (positive volume)
  std::string reason;    ///< why not, empty when all hold
  double volume = 0.0;   ///< exact volume rounded to double (0 when not closed)
  bool ok() const { return closed && convex && outward; }
};

struct OverlapRecord {
  std::size_t a = 0, b = 0;       ///< indices of the two meshes (a < b)
  double volume = 0.0;            ///< exact volume of the intersection, rounded to double
  double ratio_to_smaller = 0.0;  ///< volume / min(vol a, vol b)
};

struct CertificationReport {
  std::vector<ConvexityVerdict> meshes;
  std::vector<OverlapRecord> overlaps;  ///< pairs whose interiors intersect (exact), sorted by (a, b)
  std::size_t pairs_tested_exactly = 0; ///< pairs not settled by the bounding-box / face-plane filters
  bool certified() const;
};

/// Exact convexity verdict of one mesh.
ConvexityVerdict check_convexity(const Mesh& mesh);

/// Full certification: convexity of every mesh and exact pairwise interior-disjointness
/// (overlap volumes are computed for non-convex meshes too, on their convex hulls, and the
/// verdict then says the mesh is not convex).
CertificationReport certify(const std::vector<Mesh>& meshes);

}  // namespace dcshell
