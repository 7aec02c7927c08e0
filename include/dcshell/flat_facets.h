// Stage "remesh", step 3: fat triangulations of the (nearly) flat facets of a convex shell.
//
// A cut face is a convex polygon whose corners all lie on its boundary, rounded to doubles within
// a rounding unit of the cut plane: its triangulation is whatever that rounding noise makes the
// hull, usually fans of slivers, and no vertex may move out (the cut plane) or far in (the shell
// must keep its volume). But every triangulation of a convex polygon is *regular*: there are
// heights over the polygon whose upper hull is exactly that triangulation. So the fattest
// triangulation (area-weighted, found by dynamic programming) is made the hull's by moving each
// corner a tiny distance (a "dome" about 1e-9 of the facet's size deep) along the line where its
// other faces meet, which leaves the neighbouring faces' planes where they were.
#pragma once
#include <cstddef>

#include "dcshell/kernel.h"
#include "dcshell/simplify.h"

namespace dcshell {

struct FlatFacetOptions {
  /// Neighbouring triangles whose normals differ by less than this (radians) form one facet.
  double flat_angle = 1e-6;
  /// Depth of the dome relative to the facet's diameter (raised where the facet is less flat,
  /// its coordinates large or its triangulation's weakest fold weak) ...
  double depth = 1e-9;
  /// ... up to this outward (it costs only volume) and max_sink inward (the shell then no longer
  /// contains its input by that much); a facet that would need more is left as it is.
  double max_depth = 1e-6;
  double max_sink = 1e-8;
  /// A facet that cannot bulge outward (it lies on a constraint plane: a cut face, a face
  /// shared with a neighbour) may sink inward by at most the dome depth. Off where the shell must
  /// enclose its input exactly (a part's hull before cutting).
  bool allow_inward = true;
  /// Upper bound on the volume of the result (the remesh budget); +inf for none.
  double max_volume = 0;
  /// Faces the result may have beyond the input's: each Steiner point (a point inside a facet,
  /// on its dome) costs two. They go where they gain the most area x fatness.
  std::size_t extra_faces = 0;
  /// Points the result must still enclose besides the mesh's own vertices that do not sink
  /// (exactly): a remeshed shell's input points away from its constraint planes, which may lie
  /// on a face next to a sinking facet and would be cut off by its tilt.
  std::vector<Point3> enclose;
};

struct FlatFacetStats {
  std::size_t facets = 0;          ///< facets of two or more triangles with all corners on their boundary
  std::size_t outward = 0, inward = 0;  ///< facets re-triangulated by an outward / inward dome
  double max_inward = 0;           ///< largest inward displacement of a vertex (model units)
  std::size_t steiner = 0;         ///< Steiner points added
  double fatness_before = 0, fatness_after = 0;
};

/// Re-triangulates every facet of a closed, exactly convex triangle mesh (two or more triangles
/// whose normals agree within flat_angle, every vertex on the facet's boundary) by its fattest
/// triangulation, made the hull's by a dome; with options.extra_faces, the facets that gain most
/// get interior points too (their Delaunay triangulation, domed by a paraboloid). The result is
/// the convex hull (exact predicates) of the moved points: closed and exactly convex, with every
/// vertex of the input plus the Steiner points and at most extra_faces more faces; every
/// moved or added point satisfies `constraints` exactly, its volume is at most options.max_volume (when
/// positive), and it is returned only when its weighted fatness is higher; otherwise `mesh`
/// comes back unchanged. Deterministic (no dependence on addresses).
Mesh fatten_flat_facets(const Mesh& mesh, const ShellConstraints& constraints, const FlatFacetOptions& options = {},
                        FlatFacetStats* stats = nullptr);

}  // namespace dcshell
