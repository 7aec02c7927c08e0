#include "dcshell/mesh_volume.h"

#include <cmath>

namespace dcshell {

CGAL::Mpzf six_signed_volume(const Mesh& mesh) {
  CGAL::Mpzf six(0);
  for (auto f : mesh.faces()) {
    auto h = mesh.halfedge(f);
    const Point3& a = mesh.point(mesh.source(h));
    for (auto g = mesh.next(h); mesh.target(g) != mesh.source(h); g = mesh.next(g)) {
      const Point3& b = mesh.point(mesh.source(g));
      const Point3& c = mesh.point(mesh.target(g));
      // det[a, b, c] summed over a closed surface is 6 * volume.
      CGAL::Mpzf ax(a.x()), ay(a.y()), az(a.z()), bx(b.x()), by(b.y()), bz(b.z()), cx(c.x()), cy(c.y()), cz(c.z());
      six += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
    }
  }
  return six;
}

double diagonal_cube_volume(const CGAL::Bbox_3& box) {
  const double diag = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                CGAL::square(box.zmax() - box.zmin()));
  return diag * diag * diag;
}

}  // namespace dcshell
