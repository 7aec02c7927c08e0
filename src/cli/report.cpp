#include "cli/report.h"

#include <cstdio>
#include <iostream>

namespace dcshell::cli {

void write_certification(JsonWriter& json, const CertificationReport& rep, const std::vector<std::string>& names) {
  json.field("certified", rep.certified());
  json.key("meshes").begin_array();
  for (std::size_t i = 0; i < rep.meshes.size(); ++i) {
    const auto& m = rep.meshes[i];
    json.begin_object()
        .field("name", names[i])
        .field("closed", m.closed)
        .field("convex", m.convex)
        .field("outward", m.outward)
        .field("volume", m.volume);
    if (!m.ok()) json.field("reason", m.reason);
    json.end_object();
  }
  json.end_array();
  json.key("overlaps").begin_array();
  for (const auto& o : rep.overlaps)
    json.begin_object()
        .field("a", names[o.a])
        .field("b", names[o.b])
        .field("volume", o.volume)
        .field("ratio_to_smaller", o.ratio_to_smaller)
        .end_object();
  json.end_array();
  json.field("pairs_tested_exactly", rep.pairs_tested_exactly);
}

void print_certification_problems(const CertificationReport& rep, const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < rep.meshes.size(); ++i)
    if (!rep.meshes[i].ok()) std::cerr << names[i] << ": " << rep.meshes[i].reason << "\n";
  for (const auto& o : rep.overlaps) {
    char buf[128];
    std::snprintf(buf, sizeof buf, " overlap: volume %.6g (%.3g of the smaller)", o.volume, o.ratio_to_smaller);
    std::cerr << names[o.a] << " and " << names[o.b] << buf << "\n";
  }
}

double seconds_since(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dcshell::cli
