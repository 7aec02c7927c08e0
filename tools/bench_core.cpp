// Benchmark of the reference checker and the volume-loss evaluator (issue: < 2 s per set).
// For every shared composite model and ACD set: median wall time over --runs runs of
// (a) certify() of the parts' hulls as `dcshell check` does on meshes, and
// (b) the exact union volume of the parts' hulls, the denominator of `dcshell volume-loss`,
//     as `automatic` computes it and by each of its two methods alone (nerve, decomposition).
// Then generated deep overlaps: plank stars of k planks that all cross one axis (a k-fold
// overlap: the nerve has 2^k - 1 terms; it is run up to k = 12), random boxes at constant
// density, 64, 128, ... of them, and 4, 8, ... UV spheres of ~1,000 faces around one point
// (the nerve run up to 8).
// Usage: bench_core [--data DIR] [--runs N] [--stars KMAX] [--boxes NMAX] [--spheres SMAX]
//                   [--set SET]...
//        (DIR defaults to ../shared/data; absent = skip; KMAX defaults to 24, NMAX to 256,
//         SMAX to 12, 0 = none; each --set adds a folder of parts, one per file, or a mesh file)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "dcshell/certify.h"
#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/load_parts.h"
#include "bench_util.h"
#include "synthetic_parts.h"
#include "dcshell/error.h"
#include "dcshell/union_volume.h"

using namespace dcshell;
using dcshell::bench::median_seconds;
namespace fs = std::filesystem;

namespace {

// Median time of the union volume by `method` on freshly built polytopes (no exact value cached
// from a previous run), and the result of the last run.
double time_union(int runs, const std::vector<Part>& parts, UnionMethod method, UnionVolume& uv) {
  return median_seconds(runs, [&] {
    std::vector<ExactPolytope> fresh;
    for (std::size_t i = 0; i < parts.size(); ++i) fresh.push_back(exact_hull(parts[i].points, int(i)));
    uv = union_volume(fresh, 1e-12, method);
  });
}

const char* kHeader =
    "| set | parts | check (median s) | overlapping pairs | union volume (median s) | method, terms | deepest overlap met | "
    "nerve only (s, terms) | decomposition only (s, pieces) |\n|---|---|---|---|---|---|---|---|---|\n";

// One table row: the check of the parts' hulls, then the union by `automatic` and by each
// method alone (the nerve only when `with_nerve`: it is exponential in the deepest overlap).
void row(const std::string& label, const std::vector<Part>& parts, int runs, bool with_nerve) {
  std::vector<Mesh> hulls;
  for (const auto& part : parts) hulls.push_back(convex_hull_mesh(part.points));
  CertificationReport rep;
  UnionVolume uv, nerve, dec;
  const double tc = median_seconds(runs, [&] { rep = certify(hulls); });
  const double tu = time_union(runs, parts, UnionMethod::automatic, uv);
  const double td = time_union(runs, parts, UnionMethod::decomposition, dec);
  std::string nerve_cell = "not run";
  if (with_nerve) {
    const double tn = time_union(runs, parts, UnionMethod::nerve, nerve);
    char cell[64];
    std::snprintf(cell, sizeof cell, "%.3f, %zu", tn, nerve.terms);
    nerve_cell = cell;
    if (std::fabs(nerve.value - dec.value) > nerve.error_bound + dec.error_bound)
      std::fprintf(stderr, "bench_core: %s: the two methods disagree: %.17g vs %.17g\n", label.c_str(), nerve.value, dec.value);
  }
  std::printf("| %s | %zu | %.3f | %zu | %.3f | %s%s, %zu | %zu | %s | %.3f, %zu |\n", label.c_str(), parts.size(), tc,
              rep.overlaps.size(), tu, to_string(uv.method), uv.exact_fallback ? " (exact)" : "", uv.terms, uv.max_clique,
              nerve_cell.c_str(), td, dec.terms);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data";
  int runs = 5, stars = 24, boxes = 256, spheres = 12;
  std::vector<fs::path> extra;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--data")) data = argv[i + 1];
    if (!std::strcmp(argv[i], "--runs")) runs = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--stars")) stars = std::max(0, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--boxes")) boxes = std::max(0, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--spheres")) spheres = std::max(0, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--set")) extra.emplace_back(argv[i + 1]);
  }
  std::vector<fs::path> sets = dcshell::bench::data_sets(data, {"composite", "acd"});
  if (sets.empty()) std::printf("no shared data at %s\n\n", data.c_str());
  sets.insert(sets.end(), extra.begin(), extra.end());
  if (!sets.empty()) std::printf("%s", kHeader);
  for (const auto& set : sets) {
    std::vector<std::string> warnings;
    std::vector<Part> parts;
    try {
      parts = load_parts({set.string()}, warnings);
    } catch (const InputError& e) {
      std::fprintf(stderr, "bench_core: error: %s\n", e.what());
      return 2;
    }
    row(set.filename().string(), parts, runs, true);
  }
  if (stars > 0 || boxes >= 64 || spheres >= 4) std::printf("\n### Generated deep overlaps\n\n%s", kHeader);
  for (int k = 4; k <= stars; k += 4) row("plank star " + std::to_string(k), dcshell::synthetic::plank_star(k, 0.002), runs, k <= 12);
  // Random boxes in a cube whose side grows with the cube root of their number: a constant
  // density, overlaps several deep everywhere.
  for (int n = 64; n <= boxes; n *= 2) {
    std::mt19937_64 rng{std::uint64_t(n)};
    row("random boxes " + std::to_string(n), dcshell::synthetic::random_boxes(rng, n, 1.6 * std::cbrt(double(n)), 0.3, 1.5), runs, true);
  }
  // Round hulls of ~1,000 faces all overlapping: every clip cuts, and the nerve's alternating
  // sum cancels enough to need rationals.
  for (int n = 4; n <= spheres; n += 4) {
    std::mt19937_64 rng{std::uint64_t(1000 + n)};
    row("spheres " + std::to_string(n), dcshell::synthetic::random_spheres(rng, n, 16, 0.3), runs, n <= 8);
  }
  return 0;
}
