// Overlap detection and validity checks of a net.
//
// Net coordinates are doubles computed by the unfolder; "interiors overlap" is decided exactly on
// those doubles (Epick 2D orientation predicates), so the answer never depends on a tolerance.
// Faces joined along a fold share their corner coordinates bit for bit and therefore touch without
// overlapping. Candidate pairs come from CGAL::box_self_intersection_d: O(n log n) in practice
// (any_overlap, the yes/no test of the search's trees, scans a sort by low x and stops at the first).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "dcshell/net.h"

namespace dcshell {

using Triangle2 = std::array<Eigen::Vector2d, 3>;

/// True when the open interiors of two triangles intersect (exact on the given doubles).
/// Touching along an edge or at a point is not an overlap. A degenerate triangle (a segment) has
/// no interior but counts as overlapping when it crosses the other triangle's interior.
bool triangle_interiors_overlap(const Triangle2& a, const Triangle2& b);

/// Pairs (f, g), f < g, of net faces whose interiors overlap, sorted; at most `max_pairs`
/// (the search stops once that many are found). Empty = overlap-free.
std::vector<std::pair<int, int>> find_net_overlaps(const Net& net,
                                                   std::size_t max_pairs = std::numeric_limits<std::size_t>::max());

/// Whether any two of the triangles have overlapping interiors: the same answer as
/// `!find_net_overlaps(net, 1).empty()` for a net with these corners, by a sweep along x that
/// stops at the first overlap (the unfolder asks this of hundreds of candidate trees a shell).
bool any_overlap(const std::vector<Triangle2>& corners);

/// Everything a checker asks of a net (issue 5 §7), each decided independently.
struct NetCheck {
  bool congruent = false;  ///< every face has its shell triangle's edge lengths (relative tol)
  bool oriented = false;   ///< every face counter-clockwise: none mirrored, none degenerate
  bool folds_shared = false;  ///< both faces of every fold edge place its ends at the same points
  bool one_piece = false;     ///< the fold edges join all faces
  bool tree = false;          ///< parent[] is a spanning tree whose edges are fold edges
  bool meets_only_along_shell_edges = false;  ///< faces sharing a net point share that shell vertex
  bool overlap_free = false;
  double max_length_error = 0;  ///< largest |net length - shell length| / shell length
  std::string problem;          ///< first failed property, human readable; empty when ok()
  bool ok() const {
    return congruent && oriented && folds_shared && one_piece && tree && meets_only_along_shell_edges &&
           overlap_free;
  }
};
NetCheck check_net(const Net& net, double length_tolerance = 1e-9);

}  // namespace dcshell
