// Private to the remesh module: one simplification pass and one smoothing sweep over a mesh,
// sharing state across passes so that work is redone only where the mesh changed (every
// LP/QP is an exact solve: they are the cost).
#pragma once
#include <map>

#include "dcshell/regularise.h"
#include "dcshell/simplify.h"
#include "remesh/star.h"

namespace dcshell::remesh_detail {

struct Candidate {
  bool ok = false;
  double cost = 0;  ///< added volume
  Point3 w;
  double d_fa = 0, d_area = 0;  ///< change in the sums of area x fatness and of area
};

/// The cone over the star's ring from the point of least added volume that stays above every
/// star face, below every face across the ring and inside the constraints (an LP, its rounded
/// answer checked exactly); with fatter_only, none unless the cone is fatter than the star.
Candidate cheapest_cone(const Mesh& m, const Star& s, const ShellConstraints& c, bool fatter_only);

class Workspace {
 public:
  explicit Workspace(Mesh& mesh);
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;

  Mesh& mesh;
  double volume;  ///< current volume (floating point, updated per change)

  /// One progressive-hull pass: collapses (cheapest first) while they fit `options`; with
  /// options.single_pass, at most one collapse per neighbourhood.
  std::size_t simplify_pass(const ShellConstraints& c, const SimplifyOptions& options, SimplifyStats& st);
  /// One constrained-smoothing sweep over all vertices.
  std::size_t regularise_sweep(const std::vector<Point3>& enclose, const ShellConstraints& c, double max_volume,
                               RegulariseStats& st);
  /// One pass of lifted edge splits (split.cpp): at most max_splits, each adding two faces and
  /// raising the area x fatness sum, an independent set (no two share a face), within max_volume.
  std::size_t split_pass(const ShellConstraints& c, double max_volume, std::size_t max_splits);
  /// One pass of lifted edge flips (flip.cpp): an independent set of flips ab -> cd, each with c
  /// lifted just above the plane of bad, raising the area x fatness sum, within max_volume.
  std::size_t flip_pass(const ShellConstraints& c, double max_volume);

 private:
  void touched(const Star& s, V w);  // the stars of w and of its ring changed
  Candidate edge_candidate(H h, const ShellConstraints& c, bool fresh);
  Candidate flip_candidate(H h, const ShellConstraints& c);  // cached by stamps (flip.cpp)
  Mesh::Property_map<V, unsigned> stamp_;    // bumped whenever the vertex's star changes
  Mesh::Property_map<V, unsigned> settled_;  // stamp at which smoothing last left it in place
  struct Cached { unsigned su, sv; Candidate c; };
  std::map<std::pair<V, V>, Cached> cache_;  // by edge (min, max)
  struct CachedFlip { V c, a, b, d; unsigned sc, sa, sb, sd; Candidate cand; };
  std::map<std::size_t, CachedFlip> flip_cache_;  // by halfedge a->b (c lifted); stamps of c, a, b, d
  bool fatter_only_ = false;                 // the cache's candidates were filtered so
};

}  // namespace dcshell::remesh_detail
