#include "dcshell/mesh_volume.h"

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

}  // namespace dcshell
