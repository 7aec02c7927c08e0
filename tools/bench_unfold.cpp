// Benchmark of the unfolder (issue 5 §6). Inputs: every model of DATA/convex, the convex hulls
// of every part of every DATA/composite model, and the paper's shells in DATA/paper-output.
// Per input and heuristic: median time, overlap-free, cut length, net hull area; the GA's
// improvement over the first net and over the best heuristic. With --shells DIR (DIR/<Model>/
// shell_*.obj, as written by `dcshell shell`): per composite model, the median total time of the
// default unfolding plus the folding check of all its DC-shells. Writes a Markdown report
// (tables + summary) to --out (default: stdout).
//
// usage: bench_unfold [--data DIR] [--shells DIR] [--out FILE] [--repeat N] [--max-faces N]
//                     [--only NAME,...] [--no-ga]
#include <boost/program_options.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "bench_util.h"
#include "dcshell/convex_hull.h"
#include "dcshell/fold_check.h"
#include "dcshell/load_parts.h"
#include "dcshell/read_mesh.h"
#include "dcshell/unfold.h"
#include "dcshell/unfold_ga.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;
using namespace dcshell;

namespace {

struct Input {
  std::string set, name;
  Mesh mesh;
};

struct Run {
  double seconds = 0;
  UnfoldStats stats;
  Net net;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

template <class F>
Run timed(int repeat, F&& f) {
  Run r;
  std::vector<double> times;
  for (int i = 0; i < repeat; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    r.net = f(&r.stats);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  r.seconds = median(times);
  return r;
}

std::string fmt(double x, int prec = 4) {
  std::ostringstream os;
  os << std::setprecision(prec) << x;
  return os.str();
}

std::vector<std::string> mesh_files(const fs::path& dir) {
  std::vector<std::string> out;
  if (!fs::is_directory(dir)) return out;
  for (auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".obj") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// Per composite model: the default unfolding (best/hull, which folding-checks its best nets)
// plus, for nets it did not check, check_folding: the total over all the model's DC-shells,
// median of `repeat` runs. This is what `dcshell unfold DIR/<Model>` does, minus file output.
std::string shells_report(const std::string& dir, int repeat) {
  std::ostringstream os;
  if (dir.empty() || !fs::is_directory(dir)) return os.str();
  os << "DC-shells of the composite models (`dcshell shell` output): default unfold + folding check of every shell, "
     << "total per model, median of " << repeat << " runs:\n\n| model | shells | faces | overlap-free | fold verified | "
     << "unfold + fold check, total | unfold only (no fold check) |\n|---|---|---|---|---|---|---|\n";
  std::vector<std::string> models;
  for (auto& e : fs::directory_iterator(dir))
    if (e.is_directory()) models.push_back(e.path().filename().string());
  std::sort(models.begin(), models.end());
  for (auto& m : models) {
    std::vector<Mesh> shells;
    for (auto& f : mesh_files(fs::path(dir) / m))
      if (fs::path(f).filename().string().rfind("shell_", 0) == 0) shells.push_back(read_mesh(f));
    if (shells.empty()) continue;
    int faces = 0, ok = 0, verified = 0;
    std::vector<double> totals, folds;
    for (int r = 0; r < repeat; ++r) {
      ok = verified = faces = 0;
      double tot = 0, fold = 0;
      for (auto& mesh : shells) {
        auto t0 = std::chrono::steady_clock::now();
        UnfoldStats st;
        Net net = unfold_convex_mesh(mesh, UnfoldOptions{}, &st);
        FoldCheckResult fc = st.fold_checks > 0 ? st.fold : check_folding(net);
        auto t1 = std::chrono::steady_clock::now();
        UnfoldOptions nets_only;
        nets_only.fold_candidates = 0;
        unfold_convex_mesh(mesh, nets_only);
        auto t2 = std::chrono::steady_clock::now();
        tot += std::chrono::duration<double>(t1 - t0).count();
        fold += std::chrono::duration<double>(t2 - t1).count();
        faces += st.faces;
        ok += st.result.overlapping_pairs == 0;
        verified += fc.verified;
      }
      totals.push_back(tot), folds.push_back(fold);
    }
    os << "| " << m << " | " << shells.size() << " | " << faces << " | " << ok << " | " << verified << " | "
       << fmt(median(totals) * 1000, 3) << " ms | " << fmt(median(folds) * 1000, 3) << " ms |\n";
    std::cerr << m << ": " << fmt(median(totals) * 1000, 3) << " ms\n";
  }
  return os.str() + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", out, shells_dir, only;
  int repeat = 3;
  int max_faces = 1 << 30;
  po::options_description opts("bench_unfold options");
  opts.add_options()("help,h", "help")("data", po::value(&data), "shared data directory")(
      "out", po::value(&out), "Markdown report file (default stdout)")("repeat", po::value(&repeat), "runs per timing (median)")(
      "max-faces", po::value(&max_faces), "skip larger inputs")("no-ga", "skip the genetic search")(
      "only", po::value(&only), "comma-separated input names (file stems) to run; default all")(
      "shells", po::value(&shells_dir), "directory of DC-shell sets DIR/<Model>/shell_*.obj (per-model totals)");
  po::variables_map vm;
  if (!dcshell::bench::parse_options(argc, argv, opts, vm)) return 0;
  if (!fs::is_directory(data)) {
    std::cerr << "bench_unfold: no data directory " << data << "\n";
    return 2;
  }

  // Inputs: the 69 of the issue (convex models + hulls of Bulbasaur, Squirtle, Cow parts), then
  // the other composite models' part hulls and the paper's shells.
  std::vector<Input> inputs;
  for (auto& f : mesh_files(fs::path(data) / "convex")) inputs.push_back({"convex", fs::path(f).stem().string(), read_mesh(f)});
  std::vector<std::string> models;
  for (auto& e : fs::directory_iterator(fs::path(data) / "composite")) models.push_back(e.path().filename().string());
  std::sort(models.begin(), models.end(), [](const std::string& a, const std::string& b) {
    auto key = [](const std::string& m) { return (m == "Bulbasaur" || m == "Squirtle" || m == "Cow" ? "0" : "1") + m; };
    return key(a) < key(b);
  });
  for (auto& m : models) {
    std::vector<std::string> warnings;
    auto parts = load_parts({(fs::path(data) / "composite" / m).string()}, warnings);
    for (auto& p : parts) {
      Mesh hull = convex_hull_mesh(p.points);
      if (!hull.is_empty()) inputs.push_back({"hull:" + m, p.name, std::move(hull)});
    }
  }
  for (auto& e : fs::directory_iterator(fs::path(data) / "paper-output"))
    for (auto& f : mesh_files(e.path())) inputs.push_back({"shell:" + e.path().filename().string(), fs::path(f).stem().string(), read_mesh(f)});
  std::stable_sort(inputs.begin(), inputs.end(), [](const Input& a, const Input& b) {
    auto rank = [](const std::string& s) {
      return s == "convex" ? 0 : (s == "hull:Bulbasaur" || s == "hull:Squirtle" || s == "hull:Cow") ? 1 : s.rfind("hull:", 0) == 0 ? 2 : 3;
    };
    return rank(a.set) < rank(b.set);
  });

  struct Config {
    std::string label;
    UnfoldHeuristic h;
    UnfoldObjective o;
  };
  std::vector<Config> configs = {{"steepest", UnfoldHeuristic::steepest, UnfoldObjective::hull_area},
                                 {"flat", UnfoldHeuristic::flat, UnfoldObjective::hull_area},
                                 {"min-perimeter", UnfoldHeuristic::min_perimeter, UnfoldObjective::cut_length},
                                 {"random", UnfoldHeuristic::random, UnfoldObjective::hull_area},
                                 {"best/hull", UnfoldHeuristic::best, UnfoldObjective::hull_area},
                                 {"best/cut", UnfoldHeuristic::best, UnfoldObjective::cut_length}};
  const bool ga = !vm.count("no-ga");
  if (ga) {
    configs.push_back({"ga/hull", UnfoldHeuristic::ga, UnfoldObjective::hull_area});
    configs.push_back({"ga/cut", UnfoldHeuristic::ga, UnfoldObjective::cut_length});
  }

  auto selected = [&](const std::string& name) {
    if (only.empty()) return true;
    std::istringstream is(only);
    for (std::string item; std::getline(is, item, ',');)
      if (item == name) return true;
    return false;
  };
  std::ostringstream table, summary;
  table << "| set | input | faces | facets |";
  for (auto& c : configs) table << " " << c.label << " |";
  table << "\n|---|---|---|---|";
  for (std::size_t i = 0; i < configs.size(); ++i) table << "---|";
  table << "\n";

  std::map<std::string, int> ok_count, ok_count69;
  std::map<std::string, std::vector<double>> hull_gain, cut_gain;  // GA vs first / vs best heuristic
  int n69 = 0, total = 0;
  for (auto& in : inputs) {
    int nf = static_cast<int>(in.mesh.number_of_faces());
    if (nf > max_faces || !selected(in.name)) continue;
    bool in69 = in.set == "convex" || in.set == "hull:Bulbasaur" || in.set == "hull:Squirtle" || in.set == "hull:Cow";
    n69 += in69;
    std::cerr << in.set << " " << in.name << " (" << nf << " faces)\n";
    std::size_t row_start = table.str().size();
    table << "| " << in.set << " | " << in.name << " | " << nf << " |";
    std::map<std::string, Run> runs;
    for (auto& c : configs) {
      UnfoldOptions o;
      o.heuristic = c.h;
      o.objective = c.o;
      // Nets only: the folding check is timed with the DC-shells below.
      o.fold_candidates = 0;
      int rep = c.h == UnfoldHeuristic::ga ? 1 : repeat;
      Run r = timed(rep, [&](UnfoldStats* st) { return unfold_convex_mesh(in.mesh, o, st); });
      if (c.label == "steepest") table << " " << r.stats.facets << " |";
      bool okk = r.stats.result.overlapping_pairs == 0;
      ok_count[c.label] += okk;
      if (in69) ok_count69[c.label] += okk;
      table << " " << fmt(r.seconds * 1000, 3) << " ms, " << (okk ? "ok" : "OVERLAP") << ", cut " << fmt(r.stats.result.cut_length)
            << ", hull " << fmt(r.stats.result.hull_area) << " |";
      runs[c.label] = std::move(r);
    }
    ++total;
    table << "\n";
    std::cerr << table.str().substr(row_start) << std::flush;  // rows as they come, for long runs
    if (ga) {
      auto& gh = runs["ga/hull"].stats;
      auto& gc = runs["ga/cut"].stats;
      hull_gain["vs first"].push_back(1 - gh.result.hull_area / gh.first.hull_area);
      hull_gain["vs best heuristic"].push_back(1 - gh.result.hull_area / runs["best/hull"].stats.result.hull_area);
      cut_gain["vs first"].push_back(1 - gc.result.cut_length / gc.first.cut_length);
      cut_gain["vs best heuristic"].push_back(1 - gc.result.cut_length / runs["best/cut"].stats.result.cut_length);
    }
  }

  summary << "## Summary\n\n";
  summary << "Overlap-free nets (one piece by construction), per heuristic, on the issue's " << n69
          << " inputs (34 convex models + hulls of Bulbasaur, Squirtle, Cow parts) / on all " << total << " inputs:\n\n";
  for (auto& c : configs) summary << "- " << c.label << ": " << ok_count69[c.label] << " / " << n69 << "; all: " << ok_count[c.label] << " / " << total << "\n";
  summary << "\n" << shells_report(shells_dir, repeat);
  if (ga) {
    auto stats = [](const std::vector<double>& v) {
      std::ostringstream os;
      double mean = 0;
      for (double x : v) mean += x;
      mean /= std::max<std::size_t>(v.size(), 1);
      int ge40 = 0, ge50 = 0;
      for (double x : v) ge40 += x >= 0.4, ge50 += x >= 0.5;
      os << "mean " << fmt(100 * mean, 3) << "%, median " << fmt(100 * median(v), 3) << "%, >= 40%: " << ge40 << ", >= 50%: " << ge50
         << " of " << v.size();
      return os.str();
    };
    summary << "\nGA (fitness = normalised hull area or cut length; seeded with the heuristics' nets):\n\n";
    for (auto& [k, v] : hull_gain) summary << "- hull area reduction " << k << ": " << stats(v) << "\n";
    for (auto& [k, v] : cut_gain) summary << "- cut length reduction " << k << ": " << stats(v) << "\n";
  }
  summary << "\nCells: median time, overlap-free, cut length, net hull area (model units).\n\n";

  std::string report = "# Unfolding benchmark\n\nGenerated by `build/tools/bench_unfold`.\n\n" + summary.str() + table.str();
  if (out.empty()) std::cout << report;
  else std::ofstream(out) << report;
  return 0;
}
