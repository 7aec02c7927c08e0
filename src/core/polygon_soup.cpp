#include "dcshell/polygon_soup.h"

#include <numeric>

namespace dcshell {

std::vector<std::vector<std::size_t>> soup_components(const PolygonSoup& soup) {
  std::vector<std::size_t> parent(soup.points.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& f : soup.faces)
    for (std::size_t k = 1; k < f.size(); ++k) parent[find(f[k])] = find(f[0]);
  std::vector<std::vector<std::size_t>> out;
  std::vector<long> comp_of_root(soup.points.size(), -1);
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    std::size_t r = find(soup.faces[f][0]);
    if (comp_of_root[r] < 0) {
      comp_of_root[r] = long(out.size());
      out.emplace_back();
    }
    out[comp_of_root[r]].push_back(f);
  }
  return out;
}


}  // namespace dcshell
