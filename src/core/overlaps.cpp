#include "dcshell/overlaps.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace dcshell {

std::vector<std::pair<std::size_t, std::size_t>> box_overlap_pairs(const std::vector<CGAL::Bbox_3>& bbs) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  std::vector<Box> boxes;
  boxes.reserve(bbs.size());
  for (std::size_t i = 0; i < bbs.size(); ++i) boxes.emplace_back(bbs[i], i);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  // Closed boxes: touching boxes are reported, so contact is decided exactly later.
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    out.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
  });
  std::sort(out.begin(), out.end());
  return out;
}

CGAL::Bbox_3 bbox(const ExactPolytope& p) {
  CGAL::Bbox_3 bb;
  for (const auto& v : p.vertices) bb += v.bbox();
  return bb;
}

std::vector<Overlap> find_overlaps(const std::vector<ExactPolytope>& polys) {
  std::vector<CGAL::Bbox_3> boxes;
  for (const auto& p : polys) boxes.push_back(p.empty() ? CGAL::Bbox_3() : bbox(p));
  std::vector<Overlap> out;
  for (auto [i, j] : box_overlap_pairs(boxes)) {
    if (polys[i].empty() || polys[j].empty()) continue;
    Overlap o;
    o.i = i;
    o.j = j;
    o.region = intersect(polys[i], polys[j]);
    if (o.region.empty()) continue;
    auto iv = volume_interval(o.region);
    o.volume = 0.5 * (iv.inf() + iv.sup());
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace dcshell
