// `dcshell unfold`: convex shells -> one-piece overlap-free nets (net_k.obj), printable sheets
// (nets.svg|pdf), a JSON report with the folding check, and optionally the folding motion.
#include <algorithm>
#include <boost/program_options.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "cli/command.h"
#include "cli/report.h"
#include "dcshell/atomic_output.h"
#include "dcshell/error.h"
#include "dcshell/fold_check.h"
#include "dcshell/json.h"
#include "dcshell/load_parts.h"
#include "dcshell/mesh_volume.h"
#include "dcshell/net_sheets.h"
#include "dcshell/parallel_for.h"
#include "dcshell/read_mesh.h"
#include "dcshell/unfold.h"
#include "dcshell/unfold_ga.h"

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace dcshell::cli {
namespace {

struct ShellResult {
  std::string input, net_file;
  Net net;
  UnfoldStats stats;
  FoldCheckResult fold;
  std::string sheet_problem;  ///< why the net is left off the sheets; empty when it is on them
  double seconds = 0;
};

std::string numbered(const std::string& prefix, std::size_t k, const std::string& ext) {
  std::ostringstream os;
  os << prefix << std::setw(3) << std::setfill('0') << k << ext;
  return os.str();
}

// Names of the frames of the folding motion: FILE's stem + _NNN + extension. Refused before any
// work when one is an input or, without --force, already exists.
std::vector<std::string> motion_frame_names(const std::string& file, int frames, bool force,
                                            const std::vector<std::string>& inputs, const std::string& out) {
  fs::path p(file);
  std::error_code ec;
  {  // The output directory is replaced as a whole at commit: frames cannot live inside it.
    const std::string dir = fs::weakly_canonical(p.parent_path().empty() ? "." : p.parent_path(), ec).string() + "/";
    const std::string target = fs::weakly_canonical(out, ec).string() + "/";
    if (dir.compare(0, target.size(), target) == 0)
      throw InputError(file + ": --motion must be outside the --out directory " + out);
  }
  std::string stem = (p.parent_path() / p.stem()).string(), ext = p.has_extension() ? p.extension().string() : ".obj";
  std::vector<std::string> names;
  for (int i = 0; i < frames; ++i) {
    names.push_back(numbered(stem + "_", static_cast<std::size_t>(i), ext));
    check_output_file(names.back(), inputs);
    if (!force && fs::exists(names.back(), ec))
      throw InputError(names.back() + ": --motion frame exists (use --force to replace it)");
  }
  return names;
}

// Frames of the folding motion, all shells side by side (each shifted along x past the previous
// one's net), one OBJ per frame, all written or none.
void write_motion(const std::vector<std::string>& names, const std::vector<ShellResult>& shells,
                  AtomicFiles& frames_out) {
  const int frames = static_cast<int>(names.size());
  std::vector<double> shift(shells.size(), 0.0);
  double x = 0;
  for (std::size_t s = 0; s < shells.size(); ++s) {
    double lo = 1e300, hi = -1e300;
    for (auto& c : shells[s].net.corners)
      for (auto& q : c) lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
    shift[s] = x - lo;
    x += (hi - lo) * 1.1;
  }
  for (int i = 0; i < frames; ++i) {
    double t = frames > 1 ? static_cast<double>(i) / (frames - 1) : 1.0;
    frames_out.write(names[i], [&](std::ostream& os) {
      os << std::setprecision(17) << "# dcshell folding motion, t = " << t << "\n";
      std::size_t base = 1;
      for (std::size_t s = 0; s < shells.size(); ++s) {
        auto faces = folded_faces(shells[s].net, t);
        os << "o " << shells[s].net.name << "\n";
        for (auto& f : faces)
          for (auto& q : f) os << "v " << q.x() + shift[s] << " " << q.y() << " " << q.z() << "\n";
        for (std::size_t f = 0; f < faces.size(); ++f, base += 3) os << "f " << base << " " << base + 1 << " " << base + 2 << "\n";
      }
    });
  }
}

// Drops the shells that enclose no volume (flat) or a negligible one (below `load_parts`' tiny fraction, 1e-12, of the cube
// of the whole set's bounding-box diagonal), warning for each; refuses a set with none left.
// Returns the input index of every shell kept.
std::vector<std::size_t> skip_flat_and_tiny(std::vector<std::string>& files, std::vector<Mesh>& meshes, bool quiet) {
  CGAL::Bbox_3 box;
  for (const auto& m : meshes)
    for (auto v : m.vertices()) box += m.point(v).bbox();
  const double scale = diagonal_cube_volume(box), fraction = LoadPartsOptions{}.tiny_volume_fraction;
  std::vector<std::size_t> index;
  std::vector<std::string> kept_files, why;
  std::vector<Mesh> kept;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const double volume = CGAL::to_double(six_signed_volume(meshes[k])) / 6;
    std::string problem;
    if (volume == 0) problem = "is flat (encloses no volume)";
    else if (std::fabs(volume) < fraction * scale) {
      char buf[112];
      std::snprintf(buf, sizeof buf, "is tiny (volume %.3g, below %.2g of the set's bounding cube)", volume, fraction);
      problem = buf;
    }
    if (!problem.empty()) {
      if (!quiet) std::cerr << "dcshell unfold: warning: " << files[k] << " " << problem << "; skipped\n";
      why.push_back(files[k] + " " + problem);
      continue;
    }
    index.push_back(k);
    kept_files.push_back(files[k]);
    kept.push_back(std::move(meshes[k]));
  }
  if (kept.empty()) {
    std::string all;
    for (const auto& w : why) all += (all.empty() ? "" : "; ") + w;
    throw InputError("no shell left to unfold: " + all);
  }
  files = std::move(kept_files);
  meshes = std::move(kept);
  return index;
}

int run_unfold(int argc, char** argv) {
  return guarded("unfold", [&] {
    po::options_description opts(
        "usage: dcshell unfold [options] --out DIR SHELL|DIR...\n\n"
        "Unfolds each closed convex shell into a one-piece net that folds back without collision.\n"
        "A file of several OBJ objects (or, without objects, connected components) is one shell each.\n"
        "Writes DIR/net_NNN.obj (the flat net, z = 0: the shell's triangles in order, corners in\n"
        "order), DIR/nets.svg or nets.pdf (printable sheets) and DIR/unfold.json (per shell: faces,\n"
        "cut length, net hull area, overlap-free, fold path verified, time).\n"
        "Exit status: 0 every net overlap-free and its folding verified, 1 otherwise, 2 bad input.\n\noptions");
    std::string heuristic = "best", objective = "hull-area", out, format = "svg", paper = "a4", motion;
    std::uint64_t seed = 1;
    int tries = 0, ga_evaluations = 0, frames = 31;
    double scale = 0, fold_slack = 0, fold_fallback_slack = 0;
    long long fold_work = 0, fold_descent_work = -1;
    opts.add_options()("help,h", "show this help")("out,o", po::value(&out), "output directory (created atomically)")(
        "no-timings", "leave times out of unfold.json (byte-identical reruns)")(
        "force,f", "replace an existing non-empty output directory")(
        "quiet,q", "no warnings or summary on stderr (errors only; the exit status and unfold.json tell the rest)")(
        "heuristic", po::value(&heuristic)->default_value("best"),
        "steepest|flat|min-perimeter|random|greedy|ga|best (best: every heuristic with retries; ga: then a genetic search; greedy: overlap-aware Kruskal, longest fold first, refusing folds that overlap)")(
        "objective", po::value(&objective)->default_value("hull-area"), "hull-area|cut-length: what 'best' minimises")(
        "seed", po::value(&seed)->default_value(1), "random seed (results are reproducible)")(
        "tries", po::value(&tries)->default_value(0), "cut trees per heuristic (0 = automatic)")(
        "ga-evaluations", po::value(&ga_evaluations)->default_value(0), "nets the genetic search evaluates (0 = automatic)")(
        "format", po::value(&format)->default_value("svg"), "sheet format: svg|pdf")(
        "paper", po::value(&paper)->default_value("a4"), "paper: a3|a4|a5|letter|legal|WxHmm")(
        "scale", po::value(&scale), "millimetres per model unit (default: --fit)")(
        "fit", "largest common scale at which every piece fits on a page")("no-tabs", "no glue tabs")(
        "motion", po::value(&motion), "write the folding motion as numbered OBJ frames FILE_000.obj...")(
        "motion-frames", po::value(&frames)->default_value(31), "frames of the motion (>= 2)")(
        "fold-slack", po::value(&fold_slack)->default_value(UnfoldOptions{}.fold_slack),
        "check the folding of nets up to this fraction worse (objective) than the best; 0: the best only")(
        "fold-fallback-slack", po::value(&fold_fallback_slack)->default_value(UnfoldOptions{}.fold_fallback_slack),
        "when no net within --fold-slack folds, check nets up to this fraction worse, with a second budget (<= --fold-slack: no fallback)")(
        "fold-work", po::value(&fold_work)->default_value(UnfoldOptions{}.fold_work),
        "work budget of the folding checks per 200 faces of a shell, at most 3x this per shell (pieces placed; a count, not a time)")(
        "fold-descent-work", po::value(&fold_descent_work)->default_value(UnfoldOptions{}.fold_descent_work),
        "cut length: budget of the edge-swap descent from the verified net, scaled like --fold-work (0: none; negative: 2x --fold-work)")(
        "one-objective", "when no net of --objective folds, do not try the other objective's selection (best, ga)");
    std::vector<std::string> inputs;
    po::variables_map vm;
    if (!parse_command_line(argc, argv, opts, inputs, vm)) return 0;

    // Options first: a usage error writes nothing.
    UnfoldOptions uo;
    SheetOptions so;
    try {
      uo.heuristic = parse_unfold_heuristic(heuristic);
      uo.objective = parse_unfold_objective(objective);
      so = SheetOptions::paper_from_string(paper);
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
    uo.seed = seed;
    uo.tries = tries;
    if (!(fold_slack >= 0) || !std::isfinite(fold_slack)) throw InputError("--fold-slack must be a finite number >= 0");
    if (fold_work < 0) throw InputError("--fold-work must be >= 0");
    uo.fold_descent_work = fold_descent_work;
    if (!(fold_fallback_slack >= 0) || !std::isfinite(fold_fallback_slack))
      throw InputError("--fold-fallback-slack must be a finite number >= 0");
    uo.fold_slack = fold_slack;
    uo.fold_fallback_slack = fold_fallback_slack;
    uo.fold_work = fold_work;
    uo.fold_other_objective = !vm.count("one-objective");
    if (out.empty()) throw InputError("--out DIR is required (see 'dcshell unfold --help')");
    if (inputs.empty()) throw InputError("no input shells (see 'dcshell unfold --help')");
    if (format == "svg") so.format = SheetOptions::Format::svg;
    else if (format == "pdf") so.format = SheetOptions::Format::pdf;
    else throw InputError("unknown format '" + format + "' (svg|pdf)");
    if (vm.count("scale") && vm.count("fit")) throw InputError("--scale and --fit exclude each other");
    if (vm.count("scale") && !(scale > 0 && std::isfinite(scale))) throw InputError("--scale must be a positive number of mm per unit");
    so.scale_mm_per_unit = vm.count("scale") ? scale : 0.0;
    so.tabs = !vm.count("no-tabs");
    if (tries < 0 || ga_evaluations < 0) throw InputError("--tries and --ga-evaluations must be >= 0");
    if (vm.count("motion") && frames < 2) throw InputError("--motion-frames must be at least 2");

    const bool timings = !vm.count("no-timings");
    const bool quiet = vm.count("quiet") > 0;
    auto t0 = std::chrono::steady_clock::now();
    // One shell per object, as `check` and `remesh` read them: a file holding several (a
    // `shells.obj`, a V-HACD output) is a set of shells. `files` names each shell ("file" or
    // "file#object"), `labels` is what its net is called, `paths` are the files (never written).
    const std::vector<std::string> paths = expand_inputs(inputs);
    std::vector<std::string> files, labels;
    std::vector<Mesh> meshes;
    for (const auto& path : paths) {
      auto objects = read_mesh_objects(path);
      const std::string stem = fs::path(path).stem().string();
      for (auto& [name, mesh] : objects) {
        // An object is named by its group; a bare component number gets the file's stem.
        const std::string object = objects.size() == 1 ? "" : name.substr(path.size() + 1);
        const bool numbered_component =
            !object.empty() && std::all_of(object.begin(), object.end(), [](unsigned char c) { return std::isdigit(c); });
        labels.push_back(object.empty() ? stem : numbered_component ? stem + "_" + object : object);
        files.push_back(name);
        meshes.push_back(std::move(mesh));
      }
    }
    // Input index of each shell kept: a flat or tiny shell among good ones is skipped with a
    // warning (net_k.obj keeps the input's index k).
    const std::vector<std::size_t> index = skip_flat_and_tiny(files, meshes, quiet);
    AtomicDirectory dir(out, vm.count("force") > 0, paths);
    std::vector<std::string> protect = paths;
    protect.insert(protect.end(), inputs.begin(), inputs.end());
    const std::vector<std::string> frame_names =
        motion.empty() ? std::vector<std::string>{} : motion_frame_names(motion, frames, vm.count("force") > 0, protect, out);
    AtomicFiles frames_out(protect);

    std::vector<ShellResult> shells(files.size());
    // Shells are independent: one per core, each writing only its own slot (the output does not
    // depend on the scheduling), the largest first (a 1,300-face shell can take most of a
    // model's time); an input error is reported for the first failing shell in that order.
    std::vector<double> faces(files.size());
    for (std::size_t k = 0; k < files.size(); ++k) faces[k] = static_cast<double>(meshes[k].number_of_faces());
    const std::vector<std::size_t> order = largest_first(faces);
    parallel_for(files.size(), [&](std::size_t j) {
      const std::size_t k = order[j];
      auto& s = shells[k];
      s.input = files[k];
      auto ts = std::chrono::steady_clock::now();
      try {
        if (uo.heuristic == UnfoldHeuristic::ga) {
          GaOptions ga;
          ga.evaluations = ga_evaluations;
          s.net = unfold_ga(meshes[k], uo, ga, &s.stats);
        } else {
          s.net = unfold_convex_mesh(meshes[k], uo, &s.stats);
        }
      } catch (const InputError& e) {
        throw InputError(input_error_message(files[k], 0, e.what()));
      }
      // A net the unfolder did not check (over 5,000 faces, or no candidate checked) gets one
      // check within the same work budget: undecided past it, never minutes.
      FoldCheckOptions fo;
      fo.max_work = std::max<long long>(scaled_fold_work(uo.fold_work, meshes[k].number_of_faces()), 1);
      fo.end_proof = std::max(uo.fold_screen, 0.0);  // as the selection's checks
      // Nets above FoldCheckOptions::max_pieces come back undecided without a check.
      s.fold = s.stats.fold_checks > 0 ? s.stats.fold : check_folding(s.net, fo);
      s.seconds = seconds_since(ts);
    });
    std::set<std::string> used_names;
    for (std::size_t k = 0; k < files.size(); ++k) {
      auto& s = shells[k];
      std::string name = labels[index[k]];
      if (!used_names.insert(name).second) name = numbered("shell_", index[k], "");
      used_names.insert(name);
      s.net.name = name;
      s.net_file = numbered("net_", index[k], ".obj");
      dir.write(s.net_file, [&](std::ostream& os) { write_net_obj(s.net, os); });
      // One net the sheets cannot print (a face mirrored in the plane) does not cost the others
      // their pages: it is left off, reported, and the run is not ok.
      s.sheet_problem = net_sheet_problem(s.net);
      if (!s.sheet_problem.empty())
        std::cerr << "dcshell unfold: " << files[k] << ": left off the sheets: " << s.sheet_problem << "\n";
      if (quiet) continue;
      if (!s.stats.convex)
        std::cerr << "dcshell unfold: warning: " << files[k] << " is not convex (" << s.stats.reflex_edges
                  << " reflex edges, up to " << s.stats.max_reflex_angle * 180 / M_PI << " degrees); unfolded anyway\n";
      if (s.stats.result.overlapping_pairs)
        std::cerr << "dcshell unfold: " << files[k] << ": no overlap-free net found (" << s.stats.result.overlapping_pairs
                  << " overlapping face pairs in the best net)\n";
      if (!s.fold.verified) std::cerr << "dcshell unfold: " << files[k] << ": folding not verified: " << s.fold.message << "\n";
    }

    std::vector<Net> nets;
    for (auto& s : shells)
      if (s.sheet_problem.empty()) nets.push_back(s.net);
    std::string sheet_file = so.format == SheetOptions::Format::pdf ? "nets.pdf" : "nets.svg";
    try {
      if (!nets.empty()) dir.write(sheet_file, [&](std::ostream& os) { write_net_sheets(nets, so, {}, os); });
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }

    bool all_good = true;
    for (auto& s : shells)
      all_good &= s.stats.result.overlapping_pairs == 0 && s.fold.verified && s.sheet_problem.empty();
    dir.write("unfold.json", [&](std::ostream& os) {
      JsonWriter json(os);
      json.begin_object();
      json.field("tool", "dcshell unfold");
      json.field("heuristic", heuristic).field("objective", objective).field("seed", static_cast<std::int64_t>(seed));
      if (nets.empty()) json.key("sheets").null();  // no net could be printed
      else json.field("sheets", sheet_file);
      json.key("shells").begin_array();
      for (std::size_t k = 0; k < shells.size(); ++k) {
        const auto& s = shells[k];
        json.begin_object();
        json.field("index", index[k]).field("input", s.input).field("name", s.net.name).field("net", s.net_file);
        json.field("faces", s.stats.faces).field("facets", s.stats.facets).field("flat_angle", s.stats.flat_angle);
        json.field("convex", s.stats.convex).field("reflex_edges", s.stats.reflex_edges);
        json.field("heuristic", s.stats.heuristic).field("objective", to_string(s.stats.objective));
        json.field("attempts", s.stats.attempts);
        json.field("cut_length", s.stats.result.cut_length).field("hull_area", s.stats.result.hull_area);
        json.field("overlap_free", s.stats.result.overlapping_pairs == 0)
            .field("overlapping_pairs", s.stats.result.overlapping_pairs);
        json.field("fold_path_verified", s.fold.verified).field("fold_check_steps", s.fold.steps);
        json.field("fold_fallback", s.stats.fold_fallback);
        json.field("on_sheets", s.sheet_problem.empty());
        if (!s.sheet_problem.empty()) json.field("sheet_problem", s.sheet_problem);
        if (!s.fold.verified) json.field("fold_check_t", s.fold.t).field("fold_check_problem", s.fold.message);
        json.key("first_net").begin_object();
        json.field("cut_length", s.stats.first.cut_length).field("hull_area", s.stats.first.hull_area);
        json.end_object();
        if (timings) json.field("unfold_time_s", s.stats.seconds).field("time_s", s.seconds);
        json.end_object();
      }
      json.end_array();
      json.field("all_overlap_free_and_verified", all_good);
      if (timings) json.field("time_s", seconds_since(t0));
      json.end_object();
      os << "\n";
    });
    if (!motion.empty()) write_motion(frame_names, shells, frames_out);
    dir.commit();
    frames_out.commit();
    if (!quiet) std::cerr << (all_good ? "ok: " : "NOT ok: ") << shells.size() << " nets written to " << out << "\n";
    return all_good ? 0 : 1;
  });
}

const CommandRegistration reg("unfold", "unfold convex shells into printable, overlap-free nets", run_unfold);

}  // namespace
}  // namespace dcshell::cli
