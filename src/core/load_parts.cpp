// Stage "load": files -> parts (one per file, per OBJ group, or per connected component).
#include "dcshell/load_parts.h"

#include <CGAL/Bbox_3.h>

#include <cmath>
#include <cstdio>
#include <array>
#include <filesystem>
#include <map>
#include <set>
#include <numeric>

#include "dcshell/convex_hull.h"
#include "dcshell/error.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/mesh_volume.h"
#include "dcshell/read_mesh.h"

namespace dcshell {

namespace {

std::string base_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// Points referenced by a subset of the faces, in first-reference order (deterministic).
std::vector<Point3> referenced_points(const PolygonSoup& soup, const std::vector<std::size_t>& faces) {
  std::vector<char> seen(soup.points.size(), 0);
  std::vector<Point3> pts;
  for (std::size_t f : faces)
    for (std::size_t v : soup.faces[f])
      if (!seen[v]) {
        seen[v] = 1;
        const auto& q = soup.points[v];
        pts.emplace_back(q[0], q[1], q[2]);
      }
  return pts;
}

// Edges (by point coordinates, so per-face duplicated vertices do not matter) that do not lie
// on exactly two of the faces: 0 for a closed 2-manifold surface. A part is used only through
// its convex hull, so an open or non-manifold part (Bowser's model has one) is read with a
// warning rather than refused; commands that need a surface (check, remesh, unfold) refuse it.
std::size_t bad_edges(const PolygonSoup& soup, const std::vector<std::size_t>& faces) {
  using P = std::array<double, 3>;
  std::map<std::pair<P, P>, int> uses;
  for (std::size_t f : faces) {
    const auto& F = soup.faces[f];
    for (std::size_t k = 0; k < F.size(); ++k) {
      P a = soup.points[F[k]], b = soup.points[F[(k + 1) % F.size()]];
      if (b < a) std::swap(a, b);
      ++uses[{a, b}];
    }
  }
  std::size_t bad = 0;
  for (const auto& [e, n] : uses) bad += n != 2;
  return bad;
}

// Adds a part; counts, per file, the parts that are not closed 2-manifold surfaces.
void add_part(std::vector<Part>& parts, std::map<std::string, std::vector<std::string>>& open_parts,
              const std::string& name, const std::string& file, const PolygonSoup& soup,
              const std::vector<std::size_t>& faces) {
  if (bad_edges(soup, faces)) open_parts[file].push_back(name);
  parts.push_back({name, file, referenced_points(soup, faces)});
}

}  // namespace

std::vector<Part> load_parts(const std::vector<std::string>& inputs, std::vector<std::string>& warnings,
                             const LoadPartsOptions& options) {
  std::vector<std::string> files = expand_inputs(inputs);
  if (files.empty()) throw InputError("no input files");
  std::vector<Part> parts;
  std::map<std::string, std::vector<std::string>> open_parts;  // file -> parts that are open surfaces
  if (files.size() == 1) {
    const std::string& file = files[0];
    PolygonSoup soup = read_polygon_soup(file);
    std::vector<std::vector<std::size_t>> groups;
    std::vector<std::string> names;
    if (soup.group_names.size() > 1) {
      groups.resize(soup.group_names.size());
      for (std::size_t f = 0; f < soup.faces.size(); ++f) groups[soup.face_group[f]].push_back(f);
      for (const auto& g : soup.group_names) names.push_back(base_name(file) + "#" + g);
    } else {
      groups = soup_components(soup);
      for (std::size_t c = 0; c < groups.size(); ++c)
        names.push_back(groups.size() == 1 ? base_name(file) : base_name(file) + "#" + std::to_string(c));
    }
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (groups[g].empty()) continue;
      add_part(parts, open_parts, names[g], file, soup, groups[g]);
    }
  } else {
    for (const auto& file : files) {
      PolygonSoup soup = read_polygon_soup(file);
      std::vector<std::size_t> all(soup.faces.size());
      std::iota(all.begin(), all.end(), 0);
      add_part(parts, open_parts, base_name(file), file, soup, all);
    }
  }
  // Scale of the whole shape (its solid parts: a flat sheet is no measure of size), for the
  // "tiny" test.
  std::vector<bool> flat(parts.size());
  CGAL::Bbox_3 box;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    flat[i] = !spans_3d(parts[i].points);
    if (!flat[i])
      for (const auto& q : parts[i].points) box += q.bbox();
  }
  const double scale = diagonal_cube_volume(box);
  std::vector<Part> kept;
  std::vector<std::string> skipped;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Part& p = parts[i];
    if (flat[i]) {
      skipped.push_back(p.name + " is flat");
      warnings.push_back(p.source + ": part " + p.name + " is flat (its points are coplanar); skipped");
      continue;
    }
    double v = approximate_volume(exact_hull(p.points));
    const double fraction = v / scale;
    if (fraction < options.tiny_volume_fraction) {
      char buf[160];
      std::snprintf(buf, sizeof buf, " is tiny (hull volume %.3g = %.2g of the shape's bounding cube, below %.2g); skipped",
                    v, fraction, options.tiny_volume_fraction);
      skipped.push_back(p.name + " is tiny");
      warnings.push_back(p.source + ": part " + p.name + buf);
      continue;
    }
    kept.push_back(std::move(p));
  }
  // Segmented meshes have open parts: normal input, one line per file says so.
  // (Parts skipped as flat or tiny have had their warning.)
  std::set<std::string> kept_names;
  for (const auto& p : kept) kept_names.insert(p.source + "\n" + p.name);
  for (auto& [file, all_names] : open_parts) {
    std::vector<std::string> names;
    for (const auto& n : all_names)
      if (kept_names.count(file + "\n" + n)) names.push_back(n);
    if (names.empty()) continue;
    std::string list;
    for (std::size_t k = 0; k < names.size() && k < 3; ++k) list += (k ? ", " : "") + names[k];
    if (names.size() > 3) list += ", ...";
    warnings.push_back(file + ": " + std::to_string(names.size()) + " part(s) are open or non-manifold surfaces (" +
                       list + "); their convex hulls are used");
  }
  if (kept.empty()) {
    std::string why;
    for (const auto& w : skipped) why += (why.empty() ? "" : ", ") + w;
    throw InputError((files.size() == 1 ? files[0] : std::string("input")) + ": no solid part left (" + why + ")");
  }
  return kept;
}

}  // namespace dcshell
