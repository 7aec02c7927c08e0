#include "dcshell/write_obj.h"

#include <cstdio>
#include <vector>

namespace dcshell {

void write_obj(std::ostream& os, const Mesh& mesh, const std::string& object_name, std::size_t index_offset) {
  if (!object_name.empty()) os << "o " << object_name << "\n";
  std::vector<std::size_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices());
  std::size_t next = 1 + index_offset;
  char buf[96];
  for (auto v : mesh.vertices()) {
    const Point3& p = mesh.point(v);
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    os << buf;
    index[std::size_t(v)] = next++;
  }
  for (auto f : mesh.faces()) {
    os << "f";
    for (auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) os << ' ' << index[std::size_t(mesh.target(h))];
    os << "\n";
  }
}

}  // namespace dcshell
