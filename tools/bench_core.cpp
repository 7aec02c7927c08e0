// Benchmark of the reference checker and the volume-loss evaluator (issue: < 2 s per set).
// For every shared composite model and ACD set: median wall time over --runs runs of
// (a) certify() of the parts' hulls as `dcshell check` does on meshes, and
// (b) the exact union volume of the parts' hulls, the denominator of `dcshell volume-loss`.
// Usage: bench_core [--data DIR] [--runs N]   (DIR defaults to ../shared/data; absent = skip)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>

#include "dcshell/certify.h"
#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/load_parts.h"
#include "bench_util.h"
#include "dcshell/error.h"
#include "dcshell/union_volume.h"

using namespace dcshell;
using dcshell::bench::median_seconds;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::string data = "../shared/data";
  int runs = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--data")) data = argv[i + 1];
    if (!std::strcmp(argv[i], "--runs")) runs = std::max(1, std::atoi(argv[i + 1]));
  }
  if (!fs::is_directory(data)) {
    std::printf("no shared data at %s: nothing to benchmark\n", data.c_str());
    return 0;
  }
  std::printf("| set | parts | check (median s) | overlapping pairs | union volume (median s) | union terms |\n|---|---|---|---|---|---|\n");
  for (const auto& set : dcshell::bench::data_sets(data, {"composite", "acd"})) {
    std::vector<std::string> warnings;
    std::vector<Part> parts;
    try {
      parts = load_parts({set.string()}, warnings);
    } catch (const InputError& e) {
      std::fprintf(stderr, "bench_core: error: %s\n", e.what());
      return 2;
    }
    std::vector<Mesh> hulls;
    std::vector<ExactPolytope> polys;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      hulls.push_back(convex_hull_mesh(parts[i].points));
      polys.push_back(exact_hull(parts[i].points, int(i)));
    }
    CertificationReport rep;
    UnionVolume uv;
    double tc = median_seconds(runs, [&] { rep = certify(hulls); });
    double tu = median_seconds(runs, [&] {
      std::vector<ExactPolytope> fresh;  // fresh lazy numbers: no exact value cached from a previous run
      for (std::size_t i = 0; i < parts.size(); ++i) fresh.push_back(exact_hull(parts[i].points, int(i)));
      uv = union_volume(fresh);
    });
    std::printf("| %s | %zu | %.3f | %zu | %.3f | %zu |\n", set.filename().c_str(), parts.size(), tc, rep.overlaps.size(), tu,
                uv.terms);
  }
  return 0;
}
