// Fatness metric (the paper's measure of how foldable a net's triangles are).
#include "dcshell/fatness.h"

#include <cmath>

namespace dcshell {

double triangle_fatness(const Point3& a, const Point3& b, const Point3& c) {
  // Law of cosines on squared side lengths; cos A + cos B + cos C - 1 = r / R.
  const double a2 = CGAL::to_double(CGAL::squared_distance(b, c));
  const double b2 = CGAL::to_double(CGAL::squared_distance(c, a));
  const double c2 = CGAL::to_double(CGAL::squared_distance(a, b));
  const double la = std::sqrt(a2), lb = std::sqrt(b2), lc = std::sqrt(c2);
  if (!(la > 0 && lb > 0 && lc > 0)) return 0.0;
  const double f = (b2 + c2 - a2) / (2 * lb * lc) + (c2 + a2 - b2) / (2 * lc * la) + (a2 + b2 - c2) / (2 * la * lb) - 1.0;
  return f > 0 ? f : 0.0;  // a collinear triangle gives 0 up to rounding
}

void FatArea::add(const Point3& p, const Point3& q, const Point3& r) {
  const double area = std::sqrt(CGAL::to_double(CGAL::squared_area(p, q, r)));
  fa += area * triangle_fatness(p, q, r);
  a += area;
}

double weighted_fatness(const Mesh& mesh) {
  FatArea sum;
  for (auto f : mesh.faces()) {
    auto h0 = mesh.halfedge(f);
    const Point3& p = mesh.point(mesh.source(h0));
    for (auto h = mesh.next(h0); mesh.target(h) != mesh.source(h0); h = mesh.next(h))
      sum.add(p, mesh.point(mesh.source(h)), mesh.point(mesh.target(h)));
  }
  return sum.ratio();
}

}  // namespace dcshell
