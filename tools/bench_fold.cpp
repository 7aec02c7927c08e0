// Benchmark of the continuous folding check (issue 5, fold_check.h). For every convex model of
// DATA/convex and for every net of each DATA/composite model and DATA/acd set (the convex hull of each part, and
// each DC-shell built from the parts), it unfolds once (untimed, without the unfolder's own fold
// checks) and times check_folding on the net: median of --repeat runs. Per composite model it
// also times the whole "unfold + fold check" of all its shells, and unfolding them as `dcshell
// unfold` does (its fold selection: candidates checked until one verifies). Writes Markdown to --out
// (default stdout). Skips with a message (exit 0) when the data directory is absent.
//
// --threads N: the "unfold + fold check of all shells" timing runs the shells on N threads
// (parallel_for, one shell per item, as `dcshell unfold` does); default 1, sequential.
//
// usage: bench_fold [--data DIR] [--out FILE] [--repeat N] [--max-faces N] [--only NAME] [--no-shells] [--threads N]
//                   [--fold-fallback-slack F]
#include <boost/program_options.hpp>
#include <algorithm>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "bench_util.h"
#include "dcshell/build_shells.h"
#include "dcshell/convex_hull.h"
#include "dcshell/fold_check.h"
#include "dcshell/load_parts.h"
#include "dcshell/parallel_for.h"
#include "dcshell/read_mesh.h"
#include "dcshell/unfold.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;
using namespace dcshell;

namespace {

std::string fmt(double x, int prec = 3) {
  std::ostringstream os;
  os << std::setprecision(prec) << x;
  return os.str();
}

struct Row {
  std::string name;
  int faces = 0, pieces = 0, steps = 0, pairs = 0;
  double unfold_s = 0, fold_s = 0;
  FoldCheckResult fc;
};

// Unfolds (unfold time = median too) and times the fold check of the resulting net.
Row measure(const std::string& name, const Mesh& mesh, int repeat) {
  Row r;
  r.name = name;
  r.faces = static_cast<int>(mesh.number_of_faces());
  UnfoldOptions o;
  o.fold_candidates = 0;  // the check is timed separately below
  Net net;
  r.unfold_s = bench::median_seconds(repeat, [&] { net = unfold_convex_mesh(mesh, o); });
  r.fold_s = bench::median_seconds(repeat, [&] { r.fc = check_folding(net); });
  r.pieces = r.fc.pieces, r.steps = r.fc.steps, r.pairs = r.fc.pairs;
  return r;
}

void table(std::ostream& out, const std::vector<Row>& rows) {
  out << "| net | faces | pieces | unfold s | fold check s | steps | pairs | result |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    out << "| " << r.name << " | " << r.faces << " | " << r.pieces << " | " << fmt(r.unfold_s) << " | " << fmt(r.fold_s) << " | "
        << r.steps << " | " << r.pairs << " | " << (r.fc.verified ? "verified" : "NOT verified: " + r.fc.message) << " |\n";
}

std::vector<std::string> mesh_files(const fs::path& dir) {
  std::vector<std::string> out;
  for (auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".obj") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = "../shared/data", out, only;
  int repeat = 5, max_faces = 1 << 30, threads = 1;
  UnfoldOptions selection;  // the "selected" columns: as `dcshell unfold` with default options
  po::options_description opts("bench_fold options");
  opts.add_options()("help,h", "help")("data", po::value(&data), "shared data directory")(
      "out", po::value(&out), "Markdown report file (default stdout)")("repeat", po::value(&repeat), "runs per timing (median)")(
      "max-faces", po::value(&max_faces), "skip larger convex models")("only", po::value(&only), "only inputs whose name contains this")(
      "no-shells", "composite models: hull nets only (skip building DC-shells)")(
      "threads", po::value(&threads), "threads for the unfold+fold timing of all shells of a model (1 = sequential)")(
      "fold-fallback-slack", po::value(&selection.fold_fallback_slack),
      "the selected columns: fallback slack of the fold selection (0: none; default as dcshell unfold)")(
      "no-recheck-better", "the selected columns: no re-check of better undecided nets (UnfoldOptions::fold_recheck_work = 0)")(
      "improve-attempts", po::value(&selection.fold_improve_attempts),
      "the selected columns: UnfoldOptions::fold_improve_attempts (fresh trees better than the verified net; 0: none, negative: as dcshell unfold)")(
      "one-objective", "the selected columns: no second selection by the other objective (UnfoldOptions::fold_other_objective = false)");
  po::variables_map vm;
  if (!dcshell::bench::parse_options(argc, argv, opts, vm)) return 0;
  if (vm.count("no-recheck-better")) selection.fold_recheck_work = 0;
  if (vm.count("one-objective")) selection.fold_other_objective = false;
  if (!fs::is_directory(data)) {
    std::cerr << "bench_fold: no data directory " << data << "; nothing to measure\n";
    return 0;
  }
  std::ofstream file;
  if (!out.empty()) file.open(out);
  std::ostream& md = out.empty() ? std::cout : file;
  md << "# Folding check benchmark\n\nMedian of " << repeat
     << " runs per timing. `pieces`: rigid pieces (faces joined by flat folds); `steps`: states visited along t in [0, 1]; "
        "`pairs`: piece pairs examined. Unfolding uses the default heuristic without its own fold checks.\n\n";

  std::vector<Row> convex;
  int verified = 0;
  if (fs::is_directory(fs::path(data) / "convex"))
    for (auto& f : mesh_files(fs::path(data) / "convex")) {
      std::string name = fs::path(f).stem().string();
      if (!only.empty() && name.find(only) == std::string::npos) continue;
      Mesh mesh = read_mesh(f);
      if (static_cast<int>(mesh.number_of_faces()) > max_faces) continue;
      convex.push_back(measure(name, mesh, name == "cube4" ? std::min(repeat, 3) : repeat));
      verified += convex.back().fc.verified;
      std::cerr << name << ": " << fmt(convex.back().fold_s) << " s " << (convex.back().fc.verified ? "verified" : convex.back().fc.message) << "\n";
    }
  if (!convex.empty()) {
    md << "## Convex models\n\n" << verified << " of " << convex.size() << " nets verified.\n\n";
    table(md, convex);
    md << "\n";
  }

  // The composite models, then the ACD outputs (each hull a part), as "composite/NAME" paths.
  std::vector<std::string> models;
  for (const char* kind : {"composite", "acd"}) {
    const fs::path dir = fs::path(data) / kind;
    if (!fs::is_directory(dir)) continue;
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    for (auto& n : names) models.push_back(std::string(kind) + "/" + n);
  }
  if (!models.empty()) {
    std::ostringstream summary, detail;
    summary << "## Composite models and ACD sets\n\nPer model: all nets of the part hulls and of the DC-shells (default options). "
               "`fold s` sums the fold-check medians; `unfold+fold s` is the median of unfolding and checking all shells "
               "(the issue's target: < 0.1 s per model; threads: " << threads << "). The last two columns are what "
               "`dcshell unfold` does (default options: it checks candidate nets until one verifies): its nets verified and "
               "the median time of unfolding all shells that way, on the same threads.\n\n"
               "| model | set | nets | verified | fold s (sum) | max per net s | unfold+fold s | selected: verified | selected: s |\n"
               "|---|---|---|---|---|---|---|---|---|\n";
    for (auto& m : models) {
      if (!only.empty() && m.find(only) == std::string::npos) continue;
      std::vector<std::string> warnings;
      auto parts = load_parts({(fs::path(data) / m).string()}, warnings);
      std::vector<std::pair<std::string, std::vector<Mesh>>> sets;
      std::vector<Mesh> hulls;
      for (auto& p : parts) {
        Mesh h = convex_hull_mesh(p.points);
        if (!h.is_empty()) hulls.push_back(std::move(h));
      }
      sets.emplace_back("hulls", std::move(hulls));
      if (!vm.count("no-shells")) {
        ShellResult sr = build_shells(parts, ShellOptions{});
        std::vector<Mesh> shells;
        for (auto& s : sr.shells) shells.push_back(s.mesh);
        sets.emplace_back("shells", std::move(shells));
      }
      for (auto& [set, meshes] : sets) {
        std::vector<Row> rows;
        double sum = 0, worst = 0;
        int ok = 0;
        for (std::size_t i = 0; i < meshes.size(); ++i) {
          rows.push_back(measure(m + " " + set + " " + std::to_string(i), meshes[i], repeat));
          sum += rows.back().fold_s, worst = std::max(worst, rows.back().fold_s), ok += rows.back().fc.verified;
        }
        double total = bench::median_seconds(repeat, [&] {
          UnfoldOptions o;
          o.fold_candidates = 0;
          if (threads <= 1) {
            for (auto& mesh : meshes) check_folding(unfold_convex_mesh(mesh, o));
          } else {
            parallel_for(meshes.size(), [&](std::size_t i) { check_folding(unfold_convex_mesh(meshes[i], o)); },
                         static_cast<unsigned>(threads));
          }
        });
        // What `dcshell unfold` does: default options, the fold selection included (it checks
        // candidates until one verifies, then the fallback); its returned nets' verdicts.
        std::vector<char> selected_ok(meshes.size(), 0);
        std::vector<double> faces;
        for (const auto& mesh : meshes) faces.push_back(static_cast<double>(mesh.number_of_faces()));
        const std::vector<std::size_t> order = largest_first(faces);  // as `dcshell unfold` hands them out
        const double selected = bench::median_seconds(repeat, [&] {
          parallel_for(meshes.size(), [&](std::size_t j) {
            const std::size_t i = order[j];
            UnfoldStats st;
            unfold_convex_mesh(meshes[i], selection, &st);
            selected_ok[i] = st.fold.verified;
          }, static_cast<unsigned>(std::max(threads, 1)));
        });
        const long selected_verified = std::count(selected_ok.begin(), selected_ok.end(), 1);
        summary << "| " << m << " | " << set << " | " << meshes.size() << " | " << ok << " | " << fmt(sum) << " | " << fmt(worst) << " | "
                << fmt(total) << " | " << selected_verified << " | " << fmt(selected) << " |\n";
        std::cerr << m << " " << set << ": " << ok << "/" << meshes.size() << " verified, fold " << fmt(sum) << " s, unfold+fold " << fmt(total)
                  << " s; with the fold selection " << selected_verified << "/" << meshes.size() << ", " << fmt(selected) << " s\n";
        detail << "### " << m << " (" << set << ")\n\n";
        table(detail, rows);
        detail << "\n";
      }
    }
    md << summary.str() << "\n" << detail.str();
  }
  return 0;
}
