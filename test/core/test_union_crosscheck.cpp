// The union volume against an independent CGAL boolean union (Nef_polyhedron_3 on Epeck, whose
// volume is measured through CGAL's convex decomposition), on small cases always and on the
// shared Cow model when ../shared/data exists. Nef polyhedra, unlike corefinement, represent the
// non-manifold unions that touching hulls produce.
#include <boost/test/unit_test.hpp>

#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/convex_decomposition_3.h>

#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/load_parts.h"
#include "dcshell/union_volume.h"
#include "synthetic_parts.h"
#include "test_util.h"

using namespace dcshell;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using Nef = CGAL::Nef_polyhedron_3<Epeck>;
using ExactPolyhedron = CGAL::Polyhedron_3<Epeck>;

double boolean_union_volume(const std::vector<std::vector<Point3>>& point_sets) {
  Nef acc;
  for (const auto& pts : point_sets) {
    Mesh h = convex_hull_mesh(pts);
    ExactPolyhedron e;
    CGAL::copy_face_graph(h, e);
    acc += Nef(e);
  }
  // Volume of the Nef solid: split it into convex pieces and add their volumes.
  CGAL::convex_decomposition_3(acc);
  Epeck::FT total = 0;
  auto ci = ++acc.volumes_begin();  // the first volume is the unbounded outside
  for (; ci != acc.volumes_end(); ++ci) {
    if (!ci->mark()) continue;
    ExactPolyhedron piece;
    acc.convert_inner_shell_to_polyhedron(ci->shells_begin(), piece);
    auto f0 = piece.facets_begin()->halfedge()->vertex()->point();
    for (auto f = piece.facets_begin(); f != piece.facets_end(); ++f) {
      auto h = f->halfedge();
      auto a = h->vertex()->point();
      for (auto g = h->next(); g->next() != h; g = g->next())
        total += CGAL::volume(f0, a, g->vertex()->point(), g->next()->vertex()->point());
    }
  }
  return CGAL::to_double(total);
}

double our_union_volume(const std::vector<std::vector<Point3>>& point_sets) {
  std::vector<ExactPolytope> p;
  for (const auto& pts : point_sets) p.push_back(exact_hull(pts));
  return union_volume(p).value;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(union_crosscheck)

BOOST_AUTO_TEST_CASE(boxes_and_a_tilted_prism_against_corefinement) {
  using dcshell::test::box_points;
  std::vector<std::vector<Point3>> sets{box_points(0, 0, 0, 2, 1, 1), box_points(1, 0.25, 0.25, 2.5, 2, 1.25),
                                        box_points(0.5, 0.5, -0.5, 1.75, 1.5, 0.75)};
  // A tetrahedron-like blob crossing all three.
  sets.push_back({{0.3, 0.2, 0.1}, {2.2, 0.4, 0.3}, {1.1, 1.9, 0.2}, {1.2, 0.7, 1.6}, {0.9, 0.8, -0.4}});
  BOOST_TEST(our_union_volume(sets) == boolean_union_volume(sets), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(plank_star_against_nef_union) {
  // Twelve planks sharing one region around their common axis (4095 nerve terms): the
  // automatic union takes the convex decomposition, which must agree with the Nef union.
  std::vector<std::vector<Point3>> sets;
  std::vector<ExactPolytope> p;
  for (const auto& plank : synthetic::plank_star(12, 0.005)) {
    sets.push_back(plank.points);
    p.push_back(exact_hull(plank.points));
  }
  const UnionVolume u = union_volume(p);
  BOOST_TEST((u.method == UnionMethod::decomposition));
  BOOST_TEST(u.value == boolean_union_volume(sets), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(cow_hulls_against_corefinement, *boost::unit_test::precondition(dcshell::test::shared_data_present)) {
  std::vector<std::string> w;
  auto parts = load_parts({std::string(DCSHELL_SHARED_DATA) + "/composite/Cow"}, w);
  std::vector<std::vector<Point3>> sets;
  for (const auto& p : parts) sets.push_back(p.points);
  BOOST_TEST(our_union_volume(sets) == boolean_union_volume(sets), boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_SUITE_END()
