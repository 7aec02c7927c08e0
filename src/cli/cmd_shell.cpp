// `dcshell shell`: certified DC-shells of a composite shape.
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli/command.h"
#include "cli/report.h"
#include "dcshell/atomic_output.h"
#include "dcshell/build_shells.h"
#include "dcshell/error.h"
#include "dcshell/read_mesh.h"
#include "dcshell/write_obj.h"

namespace po = boost::program_options;

namespace dcshell::cli {
namespace {

std::string shell_name(std::size_t k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "shell_%03zu", k);
  return buf;
}

void write_report(std::ostream& os, const ShellResult& r, const std::vector<Part>& parts, const ShellOptions& opt,
                  const std::vector<std::string>& inputs, const std::vector<std::string>& warnings, bool timings) {
  JsonWriter json(os);
  json.begin_object().field("tool", "dcshell shell").field("version", DCSHELL_VERSION);
  json.key("inputs").begin_array();
  for (const auto& in : inputs) json.value(in);
  json.end_array();
  json.key("options")
      .begin_object()
      .field("method", to_string(opt.cut.method))
      .field("lambda", opt.cut.lambda)
      .field("svm_c", opt.cut.svm_c)
      .field("svm_samples", opt.cut.svm_samples)
      .field("seed", static_cast<std::int64_t>(opt.cut.seed))
      .field("max_sweeps", opt.sweep.max_sweeps)
      .field("global_sweeps", opt.sweep.global_sweeps)
      .field("starts", opt.sweep.second_start ? opt.sweep.constructive_start ? 3 : 2 : 1)
      .field("sweep_tolerance", opt.sweep.tolerance)
      .field("absorb_fraction", opt.absorb_fraction)
      .field("simplify_iterations", opt.simplify_iterations)
      .field("max_volume_increase", opt.max_volume_increase)
      .end_object();
  json.key("warnings").begin_array();
  for (const auto& w : warnings) json.value(w);
  json.end_array();
  // Parts: what became of each.
  std::vector<std::string> status(parts.size(), "vanished");
  std::vector<long> shell_of(parts.size(), -1);
  for (std::size_t k = 0; k < r.shells.size(); ++k) shell_of[r.shells[k].part] = long(k);
  json.key("parts").begin_array();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    json.begin_object().field("index", i).field("name", parts[i].name).field("source", parts[i].source);
    if (shell_of[i] >= 0) {
      json.field("status", "shell").field("shell", shell_name(std::size_t(shell_of[i])));
    } else {
      bool absorbed = false;
      for (const auto& a : r.absorbed)
        if (a.part == i) {
          json.field("status", "absorbed")
              .field("container", parts[a.container].name)
              .field("fraction_inside", a.fraction_inside);
          if (shell_of[a.container] >= 0) json.field("shell", shell_name(std::size_t(shell_of[a.container])));
          absorbed = true;
        }
      if (!absorbed) json.field("status", "vanished");
    }
    json.end_object();
  }
  json.end_array();
  json.key("shells").begin_array();
  for (std::size_t k = 0; k < r.shells.size(); ++k) {
    const Shell& s = r.shells[k];
    json.begin_object().field("name", shell_name(k)).field("file", shell_name(k) + ".obj");
    json.key("parts").begin_array().value(parts[s.part].name);
    for (auto a : s.absorbed) json.value(parts[a].name);
    json.end_array();
    json.field("volume", s.volume).field("vertices", s.mesh.number_of_vertices()).field("faces", s.mesh.number_of_faces());
    json.key("cut_planes").begin_array();
    for (const auto& c : s.cuts)
      json.begin_object()
          .field("normal", std::vector<double>{c.plane.normal.x(), c.plane.normal.y(), c.plane.normal.z()})
          .field("offset", c.plane.offset)
          .field("keeps", "normal.x <= offset")
          .field("partner", parts[c.partner].name)
          .end_object();
    json.end_array();
    json.field("rounding_nudged_vertices", s.trim.nudged_vertices);
    json.field("merged_close_vertices", s.trim.merged_vertices);
    json.field("dropped_flat_vertices", s.trim.flat_vertices);
    if (s.remeshed)
      json.key("remesh")
          .begin_object()
          .field("faces_before", s.remesh.faces_before)
          .field("faces_after", s.remesh.faces_after)
          .field("fatness_before", s.remesh.fatness_before)
          .field("fatness_after", s.remesh.fatness_after)
          .field("volume_increase", s.remesh.volume_increase())
          .field("domed_facets", s.remesh.flat.outward + s.remesh.flat.inward)
          .field("max_sink", s.remesh.flat.max_inward)
          .end_object();
    json.end_object();
  }
  json.end_array();
  json.field("overlapping_pairs", r.overlapping_pairs)
      .field("sweeps", r.sweep.sweeps)
      .field("sweep_gains", r.sweep.gains)
      .field("sweep_refits", r.sweep.refits)
      .field("sweep_start", to_string(r.sweep.start))
      .field("union_volume", r.union_volume)
      .field("shells_volume", r.shells_volume)
      .field("volume_loss", r.volume_loss)
      .field("volume_loss_error_bound", r.volume_loss_error_bound)
      .field("volume_loss_exact", r.volume_loss_exact);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < r.shells.size(); ++k) names.push_back(shell_name(k));
  json.key("certification").begin_object();
  write_certification(json, r.certification, names);
  json.end_object();
  json.field("certified", r.certification.certified());
  if (timings) {
    json.key("time_s").begin_object();
    double total = 0;
    for (const auto& t : r.times) {
      json.field(t.stage, t.seconds);
      total += t.seconds;
    }
    json.field("total", total).end_object();
  }
  json.end_object();
}

int run_shell(int argc, char** argv) {
  return guarded("shell", [&] {
    po::options_description opts(
        "usage: dcshell shell [options] --out DIR INPUT...\n\n"
        "Builds pairwise interior-disjoint convex shells (DC-shells) of a composite shape and certifies\n"
        "them exactly as written. INPUT: several mesh files (one part each), or one file (its OBJ\n"
        "groups, else its connected components), or directories of mesh files.\n"
        "Writes DIR/shell_NNN.obj, DIR/shells.obj (all shells as objects) and DIR/report.json.\n"
        "Exit status: 0 certified, 1 not certified (only report.json is written), 2 bad input.\n\noptions");
    std::vector<std::string> inputs;
    std::string out, method = "full";
    ShellOptions opt;
    std::uint64_t seed = 1;
    int starts = 3;
    opts.add_options()("help,h", "show this help")("out,o", po::value(&out), "output directory (required)")(
        "method,m", po::value(&method)->default_value("full"),
        "cut-plane method: lsf | svm | exact (the paper's) | full (normal and offset optimised)")(
        "lambda", po::value(&opt.cut.lambda)->default_value(0.01), "weight of the interference term (paper Eq. 7)")(
        "svm-c", po::value(&opt.cut.svm_c)->default_value(1.0), "SVM soft-margin penalty")(
        "svm-samples", po::value(&opt.cut.svm_samples)->default_value(opt.cut.svm_samples),
        "points sampled in the two hulls of a pair for the SVM (svm, exact, full)")(
        "seed", po::value(&seed)->default_value(1), "seed of every random choice")(
        "sweeps", po::value(&opt.sweep.max_sweeps)->default_value(6), "maximum refinement sweeps (exact, full)")(
        "sweep-tolerance", po::value(&opt.sweep.tolerance)->default_value(opt.sweep.tolerance),
        "stop the sweeps once one gains less than this fraction of the hulls' volume")(
        "global-sweeps", "full: re-fit pairs from scratch in every sweep (slower, sometimes a little less loss)")(
        "starts", po::value(&starts)->default_value(3),
        "full: sweep starts where hulls overlap heavily: 1 the pairwise planes, 2 also reshaped pairs re-fitted, "
        "3 also planes placed pair by pair (the best start is kept)")(
        "absorb-fraction", po::value(&opt.absorb_fraction)->default_value(0.99),
        "absorb a part whose hull has at least this fraction inside one other hull")(
        "simplify-iterations", po::value(&opt.simplify_iterations)->default_value(0),
        "simplify + regularise hulls and shells (paper: 10; 0 = off)")(
        "max-volume-increase", po::value(&opt.max_volume_increase)->default_value(0.05),
        "volume increase allowed to remeshing (paper: 0.05): each shell against its part's hull cut by the same planes")(
        "no-domes", "remeshing keeps cut faces exactly where they were (no fattest re-triangulation by 1e-9 domes)")(
        "no-splits", "remeshing splits no edges (no lifted points on the worst slivers' long edges)")(
        "no-flips", "remeshing flips no edges (no vertex raised to turn a long thin pair of faces)")(
        "force,f", "replace a non-empty output directory")("quiet,q", "no progress or warnings on stderr")(
        "no-timings", "leave per-stage times out of report.json (byte-identical reruns)");
    po::variables_map vm;
    if (!parse_command_line(argc, argv, opts, inputs, vm)) return 0;
    if (out.empty()) throw InputError("missing --out DIR");
    if (inputs.empty()) throw InputError("no input (see 'dcshell shell --help')");
    opt.fatten_flat_facets = vm.count("no-domes") == 0;
    opt.edge_splits = vm.count("no-splits") == 0;
    opt.edge_flips = vm.count("no-flips") == 0;
    opt.cut.method = parse_cut_method(method);
    opt.cut.seed = seed;
    // `!(x >= 0)` also refuses NaN; infinities are refused explicitly (they would reach the
    // report as null and the optimisers as overflow).
    if (!(opt.cut.lambda >= 0) || !std::isfinite(opt.cut.lambda)) throw InputError("--lambda must be a finite number >= 0");
    if (!(opt.cut.svm_c > 0) || !std::isfinite(opt.cut.svm_c)) throw InputError("--svm-c must be a finite number > 0");
    if (opt.cut.svm_samples < 32 || opt.cut.svm_samples > 10000000)
      throw InputError("--svm-samples must be in [32, 1e7]");
    if (opt.sweep.max_sweeps < 0) throw InputError("--sweeps must be >= 0");
    if (!(opt.sweep.tolerance >= 0) || !std::isfinite(opt.sweep.tolerance))
      throw InputError("--sweep-tolerance must be a finite number >= 0");
    if (!(opt.absorb_fraction > 0 && opt.absorb_fraction <= 1)) throw InputError("--absorb-fraction must be in (0, 1]");
    if (opt.simplify_iterations < 0) throw InputError("--simplify-iterations must be >= 0");
    if (!(opt.max_volume_increase >= 0) || !std::isfinite(opt.max_volume_increase))
      throw InputError("--max-volume-increase must be a finite number >= 0");
    opt.sweep.global_sweeps = vm.count("global-sweeps") > 0;
    if (starts < 1 || starts > 3) throw InputError("--starts must be 1, 2 or 3");
    opt.sweep.second_start = starts >= 2;
    opt.sweep.constructive_start = starts >= 3;
    const bool quiet = vm.count("quiet");

    std::vector<std::string> files = expand_inputs(inputs);
    AtomicDirectory dir(out, vm.count("force"), files);  // refuse a bad target before any work
    auto t0 = std::chrono::steady_clock::now();
    double last = 0;
    if (!quiet)
      opt.progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
        double t = seconds_since(t0);
        if (t < 1.0 || t - last < 0.5) return;  // only runs longer than a second report progress
        last = t;
        std::cerr << "dcshell shell: " << stage << " " << done << "/" << total << " (" << int(t) << " s)\n";
      };
    std::vector<std::string> warnings;
    std::vector<Part> parts = load_parts(files, warnings);
    if (!quiet)
      for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
    ShellResult r = build_shells(parts, opt);
    const bool certified = r.certification.certified();
    const bool timings = !vm.count("no-timings");
    if (certified) {
      std::size_t offset = 0;
      for (std::size_t k = 0; k < r.shells.size(); ++k)
        dir.write(shell_name(k) + ".obj", [&](std::ostream& os) { write_obj(os, r.shells[k].mesh); });
      dir.write("shells.obj", [&](std::ostream& os) {
        for (std::size_t k = 0; k < r.shells.size(); ++k) {
          write_obj(os, r.shells[k].mesh, shell_name(k), offset);
          offset += r.shells[k].mesh.number_of_vertices();
        }
      });
    }
    dir.write("report.json", [&](std::ostream& os) { write_report(os, r, parts, opt, inputs, warnings, timings); });
    dir.commit();
    if (!quiet) {
      for (const auto& a : r.absorbed)
        std::cerr << "note: part " << parts[a.part].name << " lies inside " << parts[a.container].name << " ("
                  << a.fraction_inside * 100 << "% of its hull); absorbed\n";
      for (auto v : r.vanished) std::cerr << "note: part " << parts[v].name << " was cut away entirely\n";
      char buf[200];
      std::snprintf(buf, sizeof buf, "%zu parts -> %zu shells, %zu overlapping pairs, volume loss %.4f%%, %s\n",
                    parts.size(), r.shells.size(), r.overlapping_pairs,
                    // a loss within rounding of zero (shells meeting exactly) printed as 0, not -0
                    std::fabs(r.volume_loss) < 5e-7 ? 0.0 : 100 * r.volume_loss,
                    certified ? "certified" : "NOT certified");
      std::cerr << buf;
      if (!certified) {
        std::vector<std::string> names;
        for (std::size_t k = 0; k < r.shells.size(); ++k) names.push_back(shell_name(k));
        print_certification_problems(r.certification, names);
      }
    }
    return certified ? 0 : 1;
  });
}

const CommandRegistration reg("shell", "build certified disjoint convex shells of a composite shape", run_shell);

}  // namespace
}  // namespace dcshell::cli
