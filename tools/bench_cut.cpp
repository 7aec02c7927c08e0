// Benchmark of the cut-plane methods on the composite models: for every pair of overlapping part
// hulls, the volume each method loses and its median CPU time over several runs. A dense search
// (many more directions and local starts than `full`) is the quality reference.
//
// Usage: bench_cut [--data DIR/composite] [--runs 5] [--model NAME] [--verbose]
// Losses are per pair, on the original hulls (no sweeps), summed over the model's pairs and
// divided by the volume of the union of the hulls.
#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>

#include "dcshell/exact_polytope.h"
#include "dcshell/fit_cut_plane.h"
#include "dcshell/load_parts.h"
#include "dcshell/polytope_clip.h"
#include "dcshell/union_volume.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;
using namespace dcshell;

namespace {

struct Method {
  std::string name;
  CutOptions options;
};

double thread_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  // Default: $DCSHELL_SHARED_DATA/composite, else ../shared/data/composite beside the repository
  // (the executable is <repo>/<build>/tools/bench_cut).
  std::string data, only;
  if (const char* env = std::getenv("DCSHELL_SHARED_DATA"))
    data = (fs::path(env) / "composite").string();
  else
    data = (fs::absolute(argv[0]).parent_path() / "../../../shared/data/composite").lexically_normal().string();
  int runs = 5;
  po::options_description desc("bench_cut options");
  desc.add_options()("help", "this help")("data", po::value(&data), "folder of composite models")(
      "runs", po::value(&runs), "timed runs per fit (median)")("model", po::value(&only), "only this model")(
      "verbose", "per-pair table")("full-directions", po::value<std::size_t>(), "override CutOptions::full_directions")(
      "full-starts", po::value<std::size_t>(), "override CutOptions::full_starts")("no-dense", "skip the dense reference");
  po::variables_map vm;
  po::store(po::parse_command_line(argc, argv, desc), vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << desc;
    return 0;
  }
  const bool verbose = vm.count("verbose") > 0;
  if (!fs::is_directory(data)) {
    std::cerr << "no data folder " << data << " (use --data)\n";
    return 1;
  }

  std::vector<Method> methods;
  for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full}) {
    CutOptions o;
    o.method = m;
    if (vm.count("full-directions")) o.full_directions = vm["full-directions"].as<std::size_t>();
    if (vm.count("full-starts")) o.full_starts = vm["full-starts"].as<std::size_t>();
    methods.push_back({to_string(m), o});
  }
  if (!vm.count("no-dense")) {
    CutOptions o;
    o.method = CutMethod::full;
    o.full_directions = 2000;
    o.full_starts = 12;
    methods.push_back({"dense", o});
  }

  std::vector<fs::path> models;
  for (const auto& e : fs::directory_iterator(data))
    if (e.is_directory() && (only.empty() || e.path().filename() == only)) models.push_back(e.path());
  std::sort(models.begin(), models.end());

  std::printf("%-11s %5s %6s |", "model", "pairs", "maxV");
  for (const auto& m : methods) std::printf(" %8s %8s |", (m.name + "%").c_str(), "ms/pair");
  std::printf("\n");
  std::map<std::string, std::vector<double>> all_times;
  for (const auto& dir : models) {
    std::vector<std::string> warnings;
    const std::vector<Part> parts = load_parts({dir.string()}, warnings);
    std::vector<ConvexPolytope> hulls;
    std::vector<ExactPolytope> exact;
    std::size_t max_vertices = 0;
    for (const auto& part : parts) {
      std::vector<Eigen::Vector3d> pts;
      for (const auto& p : part.points) pts.emplace_back(p.x(), p.y(), p.z());
      hulls.push_back(convex_hull_polytope(pts));
      max_vertices = std::max(max_vertices, hulls.back().vertices.size());
      exact.push_back(exact_hull(part.points));
    }
    const double union_vol = union_volume(exact).value;
    // Overlapping pairs with their interference regions.
    std::vector<CutProblem> problems;
    std::vector<std::pair<std::size_t, std::size_t>> ids;
    const std::size_t n = hulls.size();
    std::vector<std::vector<ConvexPolytope>> inter(n, std::vector<ConvexPolytope>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        ConvexPolytope x = intersect(hulls[i], hulls[j]);
        if (volume(x) > 1e-9 * std::min(volume(hulls[i]), volume(hulls[j]))) inter[i][j] = inter[j][i] = std::move(x);
      }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        if (inter[i][j].empty()) continue;
        CutProblem pb;
        pb.a = hulls[i];
        pb.b = hulls[j];
        pb.overlap = inter[i][j];
        for (std::size_t k = 0; k < n; ++k) {
          if (k == i || k == j) continue;
          if (!inter[i][k].empty()) pb.interference_a.push_back(inter[i][k]);
          if (!inter[j][k].empty()) pb.interference_b.push_back(inter[j][k]);
        }
        problems.push_back(std::move(pb));
        ids.emplace_back(i, j);
      }
    std::vector<double> lost(methods.size(), 0.0), ms(methods.size(), 0.0);
    std::vector<std::vector<double>> pair_lost(methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m)
      for (const auto& pb : problems) {
        std::vector<double> t;
        CutResult r;
        for (int k = 0; k < std::max(1, runs); ++k) {
          // CPU time of this thread: the machine is shared, wall time would measure the others.
          const double c0 = thread_seconds();
          r = fit_cut_plane(pb, methods[m].options);
          t.push_back(thread_seconds() - c0);
        }
        lost[m] += r.lost_volume;
        pair_lost[m].push_back(r.lost_volume);
        ms[m] += 1e3 * median(t);
        all_times[methods[m].name].push_back(1e3 * median(t));
      }
    std::printf("%-11s %5zu %6zu |", dir.filename().c_str(), problems.size(), max_vertices);
    for (std::size_t m = 0; m < methods.size(); ++m)
      std::printf(" %8.4f %8.3f |", 100 * lost[m] / union_vol, problems.empty() ? 0.0 : ms[m] / double(problems.size()));
    std::printf("\n");
    if (verbose)
      for (std::size_t p = 0; p < problems.size(); ++p) {
        std::printf("  pair %2zu-%-2zu (%3zu/%3zu vertices, %zu+%zu interference) lost/union %%:", ids[p].first,
                    ids[p].second, problems[p].a.vertices.size(), problems[p].b.vertices.size(),
                    problems[p].interference_a.size(), problems[p].interference_b.size());
        for (std::size_t m = 0; m < methods.size(); ++m)
          std::printf(" %s %.5f", methods[m].name.c_str(), 100 * pair_lost[m][p] / union_vol);
        std::printf("\n");
      }
  }
  std::printf("\nper-fit CPU time over all pairs (median / max, ms):");
  for (const auto& m : methods)
    std::printf("  %s %.3f / %.3f", m.name.c_str(), median(all_times[m.name]),
                all_times[m.name].empty() ? 0.0 : *std::max_element(all_times[m.name].begin(), all_times[m.name].end()));
  std::printf("\n");
  return 0;
}
