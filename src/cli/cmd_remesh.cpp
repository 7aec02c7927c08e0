// `dcshell remesh`: simplifies and regularises existing convex shells (progressive hull, then
// constrained smoothing) while keeping them convex, enclosing what they enclosed and disjoint
// from each other; certifies the result exactly as written.
#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>

#include "cli/command.h"
#include "cli/report.h"
#include "dcshell/atomic_output.h"
#include "dcshell/certify.h"
#include "dcshell/error.h"
#include "dcshell/json.h"
#include "dcshell/read_mesh.h"
#include "dcshell/parallel_for.h"
#include "dcshell/remesh.h"

namespace po = boost::program_options;

namespace dcshell::cli {
namespace {

// Closed triangle mesh as OBJ with round-trip precision (what was certified is what is read back).
void write_obj(std::ostream& os, const Mesh& m) {
  char buf[96];
  std::vector<std::size_t> index(m.number_of_vertices());
  std::size_t k = 0;
  for (auto v : m.vertices()) {
    index[std::size_t(v)] = ++k;
    const Point3& p = m.point(v);
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    os << buf;
  }
  for (auto f : m.faces()) {
    os << "f";
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) os << ' ' << index[std::size_t(v)];
    os << "\n";
  }
}

int run_remesh(int argc, char** argv) {
  return guarded("remesh", [&] {
    po::options_description opts(
        "usage: dcshell remesh [options] --out DIR MESH|DIR...\n\n"
        "Simplifies (progressive hull) and regularises (constrained Laplacian smoothing) existing convex\n"
        "shells. Each stays convex, encloses its input and stays disjoint from the others: for every pair,\n"
        "a plane separating them (a face they share when they touch) is kept by both. Writes\n"
        "DIR/shell_NNN.obj in input order and DIR/report.json, only if the result is certified exactly.\n"
        "Exit status: 0 certified, 1 not certified (nothing written), 2 bad input.\n\noptions");
    std::vector<std::string> inputs;
    std::string out;
    RemeshOptions ro;
    long long target_faces = 0;  // signed, so "-3" is refused instead of wrapping around
    opts.add_options()("help,h", "show this help")("out,o", po::value(&out), "output directory (required)")(
        "iterations,n", po::value(&ro.iterations)->default_value(10), "simplify + smooth rounds (the paper: 10)")(
        "max-volume-increase,r", po::value(&ro.max_volume_increase)->default_value(0.05),
        "bound on the volume increase of each shell, as a ratio (the paper: 0.05)")(
        "target-faces", po::value(&target_faces)->default_value(0), "do not simplify below this many faces (0: no bound)")(
        "no-domes", "keep flat facets on neighbour planes exactly where they were (no fattest re-triangulation by 1e-9 domes)")(
        "no-splits", "no lifted edge splits (they spend the faces collapses saved on the worst slivers)")(
        "no-flips", "no lifted edge flips (a vertex raised just enough to turn a long thin pair of faces)")(
        "no-timings", "leave times out of report.json (byte-identical reruns)")(
        "force,f", "replace an existing non-empty output directory")(
        "quiet,q", "no summary on stderr (a failure is still explained there: nothing is written then)");
    po::variables_map vm;
    if (!parse_command_line(argc, argv, opts, inputs, vm)) return 0;
    if (inputs.empty()) throw InputError("no input shells (see 'dcshell remesh --help')");
    if (out.empty()) throw InputError("--out DIR is required");
    if (ro.iterations < 0) throw InputError("--iterations must be >= 0");
    const bool timings = !vm.count("no-timings");
    if (target_faces < 0) throw InputError("--target-faces must be >= 0");
    ro.target_faces = static_cast<std::size_t>(target_faces);
    ro.fatten_flat_facets = vm.count("no-domes") == 0;
    ro.edge_splits = vm.count("no-splits") == 0;
    ro.edge_flips = vm.count("no-flips") == 0;
    if (!(ro.max_volume_increase >= 0) || !std::isfinite(ro.max_volume_increase))
      throw InputError("--max-volume-increase must be a finite number >= 0");
    AtomicDirectory dir(out, vm.count("force") > 0, inputs);  // refuses a bad target before any work

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::string> names;
    std::vector<Mesh> shells;
    for (auto& [n, m] : read_mesh_set(inputs)) {
      const ConvexityVerdict v = check_convexity(m);
      if (!v.ok()) throw InputError(n + ": not a closed outward convex polyhedron: " + v.reason);
      names.push_back(n);
      shells.push_back(std::move(m));
    }
    const CertificationReport before = certify(shells);
    if (!before.overlaps.empty()) {
      const auto& o = before.overlaps.front();
      throw InputError(names[o.a] + " and " + names[o.b] + ": input shells overlap (volume " + std::to_string(o.volume) +
                       "); remesh needs interior-disjoint shells");
    }

    std::vector<std::pair<std::size_t, std::size_t>> unseparated;
    const auto constraints = neighbour_constraints(shells, &unseparated);
    std::vector<Mesh> result(shells.size());
    std::vector<RemeshStats> stats(shells.size());
    // Two shells no plane was found between could grow into each other: they are written as
    // they came (as their hulls), rather than the whole result failing its certification.
    std::vector<char> keep_as_is(shells.size(), 0);
    for (auto [a, b] : unseparated) keep_as_is[a] = keep_as_is[b] = 1;
    parallel_for(shells.size(), [&](std::size_t i) {
      RemeshOptions o = ro;
      if (keep_as_is[i]) o.iterations = 0;
      result[i] = remesh_convex_shell(shells[i], constraints[i], o, &stats[i]);
    });
    const CertificationReport rep = certify(result);
    const double secs = seconds_since(t0);
    if (!rep.certified()) {
      print_certification_problems(rep, names);
      std::cerr << "dcshell remesh: NOT certified; nothing written\n";
      return 1;
    }
    std::vector<std::string> files;
    for (std::size_t i = 0; i < result.size(); ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "shell_%03zu.obj", i);
      files.push_back(name);
      dir.write(name, [&](std::ostream& os) { write_obj(os, result[i]); });
    }
    dir.write("report.json", [&](std::ostream& os) {
      JsonWriter json(os);
      json.begin_object();
      json.field("tool", "dcshell remesh");
      json.key("options").begin_object();
      json.field("iterations", ro.iterations).field("max_volume_increase", ro.max_volume_increase);
      json.field("target_faces", ro.target_faces);
      json.end_object();
      json.key("shells").begin_array();
      for (std::size_t i = 0; i < result.size(); ++i) {
        const RemeshStats& s = stats[i];
        json.begin_object();
        json.field("input", names[i]).field("output", files[i]);
        json.field("faces_before", s.faces_before).field("faces_after", s.faces_after);
        json.field("fatness_before", s.fatness_before).field("fatness_after", s.fatness_after);
        json.field("volume_before", s.volume_before).field("volume_after", s.volume_after);
        json.field("volume_increase", s.volume_increase());
        json.field("collapses", s.collapses).field("moves", s.moves).field("splits", s.splits).field("flips", s.flips);
        json.field("domed_facets", s.flat.outward + s.flat.inward).field("max_sink", s.flat.max_inward);
        json.field("neighbour_planes", constraints[i].cut_planes.size() + constraints[i].face_planes.size() +
                                                   constraints[i].exact_planes.size());
        json.end_object();
      }
      json.end_array();
      json.key("unseparated_pairs").begin_array();
      for (auto [a, b] : unseparated) {
        json.begin_array().value(names[a]).value(names[b]).end_array();
      }
      json.end_array();
      write_certification(json, rep, files);
      if (timings) json.field("time_s", secs);
      json.end_object();
    });
    dir.commit();
    double fb = 0, fa = 0;
    for (auto& s : stats) fb += s.fatness_before, fa += s.fatness_after;
    if (!vm.count("quiet"))
      std::cerr << "certified: " << result.size() << " shells in " << dir.target() << ", mean fatness "
                << fb / stats.size() << " -> " << fa / stats.size() << " (" << secs << " s)\n";
    return 0;
  });
}

const CommandRegistration reg("remesh", "simplify and regularise convex shells, keeping them disjoint (certified)",
                              run_remesh);

}  // namespace
}  // namespace dcshell::cli
