// Lifted edge flips (issue 4). A convex mesh's triangulation is fixed by its vertices: where a
// hull is long in one direction (a limb, a flattened sphere) it is the "Delaunay triangulation"
// of that stretched metric, long thin triangles no collapse removes (there is nothing to remove)
// and no smoothing reaches (a vertex move keeps the combinatorics). The edge ab of faces abc and
// bad becomes cd when c rises just above the plane of bad: the cone from the lifted c over its
// ring with d inserted is the flipped pair plus the rest of c's star. No face is added, the
// volume grows by about the lift x the star's area / 3, and the shell still encloses what it did
// (every old vertex is checked below every new face, exactly). The position is the progressive
// hull's LP over that star (simplify.cpp), so flips share its margins and exact checks.
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>

#include "remesh/passes.h"

namespace dcshell::remesh_detail {
namespace {

// A flip must gain at least this share of what two average faces hold (area x fatness): smaller
// ones cost an LP and volume for nothing visible. Measured on the shared models (paper pipeline,
// Bowser, Squirtle, Yoshi): 0.01 beat 0, 0.05 and 0.2.
constexpr double kMinGain = 0.01;

struct Entry {
  double key;     // -(gain per unit of added volume): best first
  std::size_t h;  // halfedge a->b of face abc, c the vertex lifted
  bool operator<(const Entry& o) const { return key != o.key ? key < o.key : h < o.h; }
};

FatArea face_pair(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  FatArea r;
  r.add(a, b, c);
  r.add(b, a, d);
  return r;
}

}  // namespace

Candidate Workspace::flip_candidate(H g, const ShellConstraints& constraints) {
  // The LP sees c's star, d and the faces across; a change there bumps the stamp of c, a, b or d
  // (touched() bumps a moved vertex's ring). What a change further off breaks, the exact check
  // before the flip catches.
  const V a = mesh.source(g), b = mesh.target(g), c = mesh.target(mesh.next(g)),
          d = mesh.target(mesh.next(mesh.opposite(g)));
  CachedFlip now{c, a, b, d, stamp_[c], stamp_[a], stamp_[b], stamp_[d], {}};
  auto same = [&](const CachedFlip& o) {  // halfedge indices are recycled: the vertices are compared too
    return o.c == now.c && o.a == now.a && o.b == now.b && o.d == now.d && o.sc == now.sc && o.sa == now.sa &&
           o.sb == now.sb && o.sd == now.sd;
  };
  auto it = flip_cache_.find(std::size_t(g));
  if (it != flip_cache_.end() && same(it->second)) return it->second.cand;
  const Star s = flip_star(mesh, g);
  now.cand = s.valid ? cheapest_cone(mesh, s, constraints, true) : Candidate{};
  flip_cache_[std::size_t(g)] = now;
  return now.cand;
}

std::size_t Workspace::flip_pass(const ShellConstraints& constraints, double max_volume) {
  if (mesh.number_of_faces() == 0) return 0;
  FatArea total;
  for (F f : mesh.faces()) {
    const H k = mesh.halfedge(f);
    total.add(mesh.point(mesh.source(k)), mesh.point(mesh.target(k)), mesh.point(mesh.target(mesh.next(k))));
  }
  const double fat = total.ratio(), min_gain = kMinGain * 2 * total.fa / double(mesh.number_of_faces());
  const double eps = 1e-12 * std::abs(volume);
  auto gain_of = [&](const FatArea& before, const FatArea& after) {
    return after.fa - before.fa - fat * (after.a - before.a);
  };

  // Rate every edge by the flip at the current positions (the lift is small), then solve the LP
  // only for those that gain: both directions, c lifted (h) or d lifted (opposite of h).
  std::vector<Entry> entries;
  for (auto e : mesh.edges()) {
    const H h = mesh.halfedge(e);
    const V a = mesh.source(h), b = mesh.target(h), c = mesh.target(mesh.next(h)),
            d = mesh.target(mesh.next(mesh.opposite(h)));
    const Point3 &pa = mesh.point(a), &pb = mesh.point(b), &pc = mesh.point(c), &pd = mesh.point(d);
    if (gain_of(face_pair(pa, pb, pc, pd), face_pair(pc, pd, pb, pa)) <= min_gain) continue;
    for (const H g : {h, mesh.opposite(h)}) {
      const Candidate cand = flip_candidate(g, constraints);
      if (!cand.ok) continue;
      const double gain = cand.d_fa - fat * cand.d_area;
      if (gain > min_gain) entries.push_back({-gain / (std::max(cand.cost, 0.0) + eps), std::size_t(g)});
    }
  }
  std::sort(entries.begin(), entries.end());

  // An independent set: no two flips share a vertex of their stars, so each one's star, LP and
  // gain are still those computed above when it is made; the exact check is redone anyway,
  // because a lifted vertex elsewhere may now lie above one of the new faces.
  std::vector<char> locked(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
  std::size_t flips = 0;
  for (const Entry& e : entries) {
    const H g(static_cast<Mesh::size_type>(e.h));
    const Star s = flip_star(mesh, g);
    if (!s.valid || locked[s.removed[0]] ||
        std::any_of(s.ring.begin(), s.ring.end(), [&](V r) { return locked[r]; }))
      continue;
    const Candidate cand = flip_candidate(g, constraints);  // unchanged: nothing in its star moved yet
    if (!cand.ok || !(cand.d_fa - fat * cand.d_area > min_gain)) continue;
    if (!replacement_is_valid(mesh, s, cand.w, {}, constraints)) continue;
    const double dv = volume_change(mesh, s, cand.w);
    if (volume + std::max(dv, 0.0) > max_volume) continue;
    const V c = s.removed[0];
    CGAL::Euler::flip_edge(g, mesh);  // ab -> cd; every other face stays
    mesh.point(c) = cand.w;
    volume += dv;
    ++flips;
    touched(s, c);
    locked[c] = 1;
    for (V r : s.ring) locked[r] = 1;
  }
  return flips;
}

}  // namespace dcshell::remesh_detail
