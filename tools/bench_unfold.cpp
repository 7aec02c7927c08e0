// Benchmark of the unfolder (issue 5 §6). Inputs: every model of DATA/convex, the convex hulls
// of every part of every DATA/composite model, and the paper's shells in DATA/paper-output.
// Per input and heuristic: median time, overlap-free, cut length, net hull area; the GA's
// improvement over the first net and over the best heuristic. With --shells DIR (DIR/<Model>/
// shell_*.obj, as written by `dcshell shell`): per composite model, the median total time of the
// default unfolding plus the folding check of all its DC-shells. Writes a Markdown report
// (tables + summary) to --out (default: stdout).
//
// usage: bench_unfold [--data DIR] [--shells DIR] [--out FILE] [--repeat N] [--max-faces N]
//                     [--only NAME,...] [--no-ga] [--issue69] [--configs LABEL,...] [--ga-evaluations N]
//                     [--digits N]
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
#include "unfold/unfold_internal.h"

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
  int ga_evaluations = 0, digits = 4;
  std::string config_list;
  po::options_description opts("bench_unfold options");
  opts.add_options()("help,h", "help")("data", po::value(&data), "shared data directory")(
      "out", po::value(&out), "Markdown report file (default stdout)")("repeat", po::value(&repeat), "runs per timing (median)")(
      "max-faces", po::value(&max_faces), "skip larger inputs")("no-ga", "skip the genetic search")(
      "only", po::value(&only), "comma-separated input names (file stems) to run; default all")(
      "shells", po::value(&shells_dir), "directory of DC-shell sets DIR/<Model>/shell_*.obj (per-model totals)")(
      "issue69", "only the issue's 69 inputs (convex models, hulls of Bulbasaur, Squirtle, Cow parts)")(
      "configs", po::value(&config_list),
      "comma-separated columns to run (steepest,flat,min-perimeter,random,greedy,best/hull,best/cut,ga/hull,ga/cut); default all")(
      "ga-evaluations", po::value(&ga_evaluations), "GA evaluation budget (0 = automatic)")(
      "digits", po::value(&digits), "significant digits of the cut lengths in the table (default 4)");
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
                                 {"greedy", UnfoldHeuristic::greedy, UnfoldObjective::cut_length},
                                 {"best/hull", UnfoldHeuristic::best, UnfoldObjective::hull_area},
                                 {"best/cut", UnfoldHeuristic::best, UnfoldObjective::cut_length}};
  if (!vm.count("no-ga")) {
    configs.push_back({"ga/hull", UnfoldHeuristic::ga, UnfoldObjective::hull_area});
    configs.push_back({"ga/cut", UnfoldHeuristic::ga, UnfoldObjective::cut_length});
  }
  auto listed = [](const std::string& list, const std::string& name) {
    std::istringstream is(list);
    for (std::string item; std::getline(is, item, ',');)
      if (item == name) return true;
    return false;
  };
  if (!config_list.empty())
    configs.erase(std::remove_if(configs.begin(), configs.end(), [&](const Config& c) { return !listed(config_list, c.label); }),
                  configs.end());
  auto has = [&](const std::string& label) {
    return std::any_of(configs.begin(), configs.end(), [&](const Config& c) { return c.label == label; });
  };
  const bool ga_hull = has("ga/hull"), ga_cut = has("ga/cut");
  const bool issue69 = vm.count("issue69") > 0;

  auto selected = [&](const std::string& name) { return only.empty() || listed(only, name); };
  std::ostringstream table, summary;
  table << "| set | input | faces | facets |";
  for (auto& c : configs) table << " " << c.label << " |";
  table << "\n|---|---|---|---|";
  for (std::size_t i = 0; i < configs.size(); ++i) table << "---|";
  table << "\n";

  std::map<std::string, int> ok_count, ok_count69;
  // GA gains vs the first net / vs the best heuristic, on all inputs and on the 69 ("/69").
  std::map<std::string, std::vector<double>> hull_gain, cut_gain, ga_seconds;
  std::vector<double> mst_gain69;  // 1 - (minimum-length cut tree, overlaps ignored) / first net
  std::vector<double> area_gain69;  // 1 - surface area / first net's hull: no net's hull is smaller
  int target69 = 0, mst_reached69 = 0;
  int n69 = 0, total = 0;
  for (auto& in : inputs) {
    int nf = static_cast<int>(in.mesh.number_of_faces());
    if (nf > max_faces || !selected(in.name)) continue;
    bool in69 = in.set == "convex" || in.set == "hull:Bulbasaur" || in.set == "hull:Squirtle" || in.set == "hull:Cow";
    if (issue69 && !in69) continue;
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
      GaOptions gao;
      gao.evaluations = ga_evaluations;
      Run r = timed(rep, [&](UnfoldStats* st) {
        return c.h == UnfoldHeuristic::ga ? unfold_ga(in.mesh, o, gao, st) : unfold_convex_mesh(in.mesh, o, st);
      });
      if (&c == &configs.front()) table << " " << r.stats.facets << " |";
      bool okk = r.stats.result.overlapping_pairs == 0;
      ok_count[c.label] += okk;
      if (in69) ok_count69[c.label] += okk;
      table << " " << fmt(r.seconds * 1000, 3) << " ms, " << (okk ? "ok" : "OVERLAP") << ", cut " << fmt(r.stats.result.cut_length, digits)
            << ", hull " << fmt(r.stats.result.hull_area) << " |";
      runs[c.label] = std::move(r);
    }
    ++total;
    table << "\n";
    std::cerr << table.str().substr(row_start) << std::flush;  // rows as they come, for long runs
    double hg = 0, cg = 0;
    auto add = [&](std::map<std::string, std::vector<double>>& m, const std::string& k, double v) {
      m[k].push_back(v);
      if (in69) m[k + " (69)"].push_back(v);
    };
    if (ga_hull) {
      auto& gh = runs["ga/hull"].stats;
      hg = 1 - gh.result.hull_area / gh.first.hull_area;
      add(hull_gain, "vs first", hg);
      if (has("best/hull")) add(hull_gain, "vs best heuristic", 1 - gh.result.hull_area / runs["best/hull"].stats.result.hull_area);
      add(ga_seconds, "ga/hull", runs["ga/hull"].seconds);
      if (in69) {
        double area = 0;
        for (auto f : in.mesh.faces()) {
          std::vector<Point3> p;
          for (auto v : in.mesh.vertices_around_face(in.mesh.halfedge(f))) p.push_back(in.mesh.point(v));
          for (std::size_t i = 1; i + 1 < p.size(); ++i) area += std::sqrt(CGAL::to_double(CGAL::squared_area(p[0], p[i], p[i + 1])));
        }
        area_gain69.push_back(1 - area / gh.first.hull_area);
      }
    }
    if (ga_cut) {
      auto& gc = runs["ga/cut"].stats;
      cg = 1 - gc.result.cut_length / gc.first.cut_length;
      add(cut_gain, "vs first", cg);
      if (has("best/cut")) add(cut_gain, "vs best heuristic", 1 - gc.result.cut_length / runs["best/cut"].stats.result.cut_length);
      add(ga_seconds, "ga/cut", runs["ga/cut"].seconds);
      if (in69) {
        // The minimum-length cut tree (overlaps ignored) bounds what any cut tree can reach.
        using namespace unfold_detail;
        ShellGraph sgr = build_shell_graph(in.mesh, gc.flat_angle);
        Rng rng(1);
        double mst = decode(sgr, folded_groups(sgr, min_perimeter_weights(sgr, rng, 0.0)), 0).metrics.cut_length;
        mst_gain69.push_back(1 - mst / gc.first.cut_length);
        mst_reached69 += gc.result.cut_length <= mst * (1 + 1e-6);  // rounding of equal lengths
      }
    }
    if (in69 && (hg >= 0.4 || cg >= 0.5)) ++target69;
  }

  summary << "## Summary\n\n";
  summary << "Overlap-free nets (one piece by construction), per heuristic, on the issue's " << n69
          << " inputs (34 convex models + hulls of Bulbasaur, Squirtle, Cow parts) / on all " << total << " inputs:\n\n";
  for (auto& c : configs) summary << "- " << c.label << ": " << ok_count69[c.label] << " / " << n69 << "; all: " << ok_count[c.label] << " / " << total << "\n";
  summary << "\n" << shells_report(shells_dir, repeat);
  if (ga_hull || ga_cut) {
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
    if (!area_gain69.empty())
      summary << "- ceiling of the hull area reduction (hull >= net area = surface area, vs first; 69): " << stats(area_gain69) << "\n";
    if (!mst_gain69.empty())
      summary << "- ceiling of the cut length reduction (minimum-length cut tree, overlaps ignored, vs first; 69): "
              << stats(mst_gain69) << "; GA cut-length nets at that minimum: " << mst_reached69 << " of " << mst_gain69.size()
              << "\n";
    if (ga_hull && ga_cut) summary << "- target \"hull area >= 40% or cut length >= 50% vs first\" met on " << target69 << " of " << n69 << " of the 69\n";
    for (auto& [k, v] : ga_seconds) {
      auto w = v;
      std::sort(w.begin(), w.end());
      summary << "- time " << k << ": median " << fmt(median(w), 3) << " s, max " << fmt(w.empty() ? 0 : w.back(), 3) << " s (" << w.size()
              << " inputs)\n";
    }
  }
  summary << "\nCells: median time, overlap-free, cut length, net hull area (model units).\n\n";

  std::string report = "# Unfolding benchmark\n\nGenerated by `build/tools/bench_unfold`.\n\n" + summary.str() + table.str();
  if (out.empty()) std::cout << report;
  else std::ofstream(out) << report;
  return 0;
}
