// Benchmark of the remesh stage on the shared composite models (issue 4).
//
// For each model: the convex hulls of its parts (what the paper's fatness plots show; the shells
// after cutting come from the pipeline), area-weighted fatness over all hulls together
//  - plain hulls,
//  - the paper's baseline: CGAL isotropic remeshing of each hull (target edge length giving about
//    the hull's own face count, 3 iterations), then the convex hull of the result,
//  - ours after 1..N iterations at each maximum volume increase (one run per ratio: the first k
//    iterations of a run do not depend on N),
// and the wall time of remeshing all hulls with the paper's setting (10 iterations, 5%), median
// of --repeat runs. Writes a Markdown table to stdout and one SVG plot per model.
//
// Then the shells the pipeline delivers (build_shells, method full), what the targets are about:
//  - plain: simplify_iterations = 0,
//  - paper: simplify_iterations = 10, max_volume_increase = 0.05 (hulls remeshed before cutting,
//    shells after), volume and faces compared with the plain shells,
//  - post: the plain shells remeshed alone with the pipeline's constraints (cut planes and
//    neighbour planes), timed (median of --repeat runs): "remeshing all shells of a model",
//  - baseline: isotropic remeshing + convex hull of each plain shell.
//
// --many-boxes N (no shared data needed): N seeded random boxes at constant density (most pairs
// of shells far apart, as in a large scene or a fine decomposition), their plain shells, then
// the time (median of --repeat) of neighbour_constraints and of remeshing every shell with the
// paper's setting, one shell per core, and how many LPs/QPs went to the exact solver.
// --random-cones N [--points P]: the same for N hulls of the apex and P seeded random points on
// cones (an apex whose star spans the cone: the enclosure rows of its QP).
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include "bench_util.h"
#include "dcshell/atomic_output.h"
#include "dcshell/build_shells.h"
#include "dcshell/convex_hull.h"
#include "dcshell/fatness.h"
#include "dcshell/load_parts.h"
#include "dcshell/parallel_for.h"
#include "dcshell/remesh.h"
#include "remesh/qp3.h"
#include "synthetic_parts.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;
namespace PMP = CGAL::Polygon_mesh_processing;
using namespace dcshell;

namespace {

// Where a set of shells' area is: on a cut face (all corners within 1e-7 of the shell's size of
// one of its cut planes), in the band a cut leaves along its boundary (some corners on a cut
// plane), or elsewhere on the hull; by fatness band, and its thin triangles (fatness < 0.2) by
// shape: needles (shortest / longest edge < 0.25), caps (an angle above 2.2 rad), others.
struct Breakdown {
  enum Where { cut, band, hull };
  enum Shape { fat, needle, cap, thin };
  struct Class {
    double a = 0, fa = 0;
    std::size_t n = 0;
  };
  Class cls[3][4];
  double fat_band[5] = {0, 0, 0, 0, 0};  // area with fatness in [0, .1), [.1, .2), ... [.4, .5]
  void add(const Mesh& m, const std::vector<CutPlane>& cuts) {
    const auto box = CGAL::bbox_3(m.points().begin(), m.points().end());
    const double size = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
    for (auto f : m.faces()) {
      auto h = m.halfedge(f);
      const Point3* P[3] = {&m.point(m.source(h)), &m.point(m.target(h)), &m.point(m.target(m.next(h)))};
      bool on_one = false, touches = false;
      for (const CutPlane& p : cuts) {
        int n = 0;
        for (const Point3* q : P) n += std::abs(p.eval({q->x(), q->y(), q->z()})) <= 1e-7 * size;
        on_one = on_one || n == 3;
        touches = touches || n > 0;
      }
      const double A = std::sqrt(CGAL::to_double(CGAL::squared_area(*P[0], *P[1], *P[2])));
      const double f_ = triangle_fatness(*P[0], *P[1], *P[2]);
      auto vec = [](const Point3* p) { return Eigen::Vector3d(p->x(), p->y(), p->z()); };
      double shortest = std::numeric_limits<double>::infinity(), longest = 0, widest = 0;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d a = vec(P[k]), u = vec(P[(k + 1) % 3]) - a, w = vec(P[(k + 2) % 3]) - a;
        shortest = std::min(shortest, u.norm()), longest = std::max(longest, u.norm());
        widest = std::max(widest, std::atan2(u.cross(w).norm(), u.dot(w)));
      }
      const Shape shape = f_ >= 0.2 ? fat : shortest < 0.25 * longest ? needle : widest > 2.2 ? cap : thin;
      Class& c = cls[on_one ? cut : touches ? band : hull][shape];
      c.a += A, c.fa += A * f_, ++c.n;
      fat_band[std::min(4, int(f_ * 10))] += A;
    }
  }
  void print(const std::string& name, const char* what) const {
    double t = 0, where_a[3] = {0, 0, 0}, where_fa[3] = {0, 0, 0};
    std::size_t where_n[3] = {0, 0, 0}, faces = 0;
    for (int w = 0; w < 3; ++w)
      for (const Class& c : cls[w]) t += c.a, where_a[w] += c.a, where_fa[w] += c.fa, where_n[w] += c.n, faces += c.n;
    std::fprintf(stderr, "%s %s: cut faces %.0f%% of area (%zu of %zu faces) at %.4f, rest at %.4f; area by fatness band:",
                 name.c_str(), what, 100 * where_a[cut] / t, where_n[cut], faces,
                 where_a[cut] > 0 ? where_fa[cut] / where_a[cut] : 0,
                 t > where_a[cut] ? (where_fa[band] + where_fa[hull]) / (t - where_a[cut]) : 0);
    for (double b : fat_band) std::fprintf(stderr, " %.0f%%", 100 * b / t);
    std::fprintf(stderr, "\n");
    // Per class: share of the area, fatness, count, and what the whole set would gain in
    // fatness if that class were equilateral (0.5).
    const char* wn[3] = {"cut", "band", "hull"};
    const char* sn[4] = {"fat", "needle", "cap", "thin other"};
    for (int w = 0; w < 3; ++w)
      for (int k = 0; k < 4; ++k)
        if (cls[w][k].n > 0)
          std::fprintf(stderr, "%s %s:   %-4s %-10s %5.1f%% of area at %.3f, %zu faces, deficit %.4f\n", name.c_str(), what,
                       wn[w], sn[k], 100 * cls[w][k].a / t, cls[w][k].fa / cls[w][k].a, cls[w][k].n,
                       (0.5 * cls[w][k].a - cls[w][k].fa) / t);
  }
};

// Area-weighted fatness accumulated over several meshes.
struct FatSum {
  double fa = 0, a = 0;
  void add(const Mesh& m) {
    const double area = CGAL::to_double(PMP::area(m));
    fa += area * weighted_fatness(m);
    a += area;
  }
  double value() const { return a > 0 ? fa / a : 0; }
};

Mesh baseline(const Mesh& hull) {
  Mesh m = hull;
  const double area = CGAL::to_double(PMP::area(m));
  const double len = std::sqrt(4 * area / (std::sqrt(3.0) * double(hull.number_of_faces())));
  PMP::isotropic_remeshing(faces(m), len, m, CGAL::parameters::number_of_iterations(3));
  return convex_hull_mesh(mesh_points(m));
}

std::string svg_plot(const std::string& title, const std::vector<double>& ratios,
                     const std::vector<std::vector<double>>& curves, double plain, double base) {
  const double W = 780, H = 400, L = 60, R = 290, T = 40, B = 50;
  double ymax = std::max(plain, base);
  for (auto& c : curves)
    for (double v : c) ymax = std::max(ymax, v);
  ymax = std::min(0.5, std::ceil(ymax * 10 + 0.5) / 10);
  const std::size_t n = curves.empty() ? 1 : curves[0].size();
  auto X = [&](double k) { return L + (W - L - R) * (k - 1) / std::max<double>(1, double(n) - 1); };
  auto Y = [&](double v) { return T + (H - T - B) * (1 - v / ymax); };
  std::ostringstream s;
  char buf[256];
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << L << "\" y=\"22\" font-size=\"15\">" << title << ": weighted fatness vs iterations</text>\n";
  for (int i = 0; i <= 5; ++i) {
    const double v = ymax * i / 5;
    std::snprintf(buf, sizeof buf, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/><text x=\"%g\" y=\"%g\" text-anchor=\"end\">%.2f</text>\n",
                  L, Y(v), W - R, Y(v), L - 6, Y(v) + 4, v);
    s << buf;
  }
  for (double k : {1.0, double(n) / 4, double(n) / 2, 3.0 * n / 4, double(n)}) {
    std::snprintf(buf, sizeof buf, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%d</text>\n", X(std::round(k)), H - B + 18, int(std::round(k)));
    s << buf;
  }
  std::snprintf(buf, sizeof buf, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">iterations</text>\n", (L + W - R) / 2, H - 10);
  s << buf;
  const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"};
  auto legend = [&](int row, const char* colour, const std::string& label, bool dashed) {
    std::snprintf(buf, sizeof buf, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" stroke-width=\"2\"%s/><text x=\"%g\" y=\"%g\">%s</text>\n",
                  W - R + 10, T + 18.0 * row, W - R + 35, T + 18.0 * row, colour, dashed ? " stroke-dasharray=\"5,4\"" : "",
                  W - R + 40, T + 18.0 * row + 4, label.c_str());
    s << buf;
  };
  for (std::size_t c = 0; c < curves.size(); ++c) {
    s << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << colours[c % 6] << "\" points=\"";
    for (std::size_t k = 0; k < curves[c].size(); ++k) s << X(double(k + 1)) << "," << Y(curves[c][k]) << " ";
    s << "\"/>\n";
    std::ostringstream lab;
    lab << "max +" << ratios[c] * 100 << "% volume";
    legend(int(c), colours[c % 6], lab.str(), false);
  }
  for (auto [v, colour, label, row] : {std::tuple{plain, "#000", "plain hulls", int(curves.size())},
                                       std::tuple{base, "#888", "baseline (isotropic+hull)", int(curves.size()) + 1}}) {
    std::snprintf(buf, sizeof buf, "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"/>\n",
                  L, Y(v), W - R, Y(v), colour);
    s << buf;
    legend(row, colour, label, true);
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace

// The pipeline's constraints for its shells: neighbour planes and the shell's own cuts.
std::vector<ShellConstraints> pipeline_constraints(const ShellResult& plain, const std::vector<Mesh>& meshes) {
  std::vector<ShellConstraints> cons = neighbour_constraints(meshes);
  for (std::size_t k = 0; k < meshes.size(); ++k)
    for (const auto& c : plain.shells[k].cuts) cons[k].cut_planes.push_back(c.plane);
  return cons;
}

// The plain shells of `parts`, remeshed with the default options: timing, solves, fatness.
int bench_synthetic(const std::vector<Part>& parts, const std::string& what, int repeat) {
  const int n = static_cast<int>(parts.size());
  const ShellResult plain = build_shells(parts, ShellOptions{});
  std::vector<Mesh> meshes;
  std::size_t faces = 0;
  for (const auto& s : plain.shells) meshes.push_back(s.mesh), faces += s.mesh.number_of_faces();
  std::vector<double> t_cons, t_remesh;
  std::vector<Mesh> post;
  std::size_t all = 0, exact = 0;
  for (int r = 0; r < repeat; ++r) {
    const std::size_t all0 = remesh_detail::all_solves(), exact0 = remesh_detail::exact_solves();
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<ShellConstraints> cons = pipeline_constraints(plain, meshes);
    const auto t1 = std::chrono::steady_clock::now();
    post.assign(meshes.size(), Mesh());
    parallel_for(meshes.size(), [&](std::size_t k) { post[k] = remesh_convex_shell(meshes[k], cons[k], RemeshOptions{}); });
    const auto t2 = std::chrono::steady_clock::now();
    t_cons.push_back(std::chrono::duration<double>(t1 - t0).count());
    t_remesh.push_back(std::chrono::duration<double>(t2 - t1).count());
    all = remesh_detail::all_solves() - all0, exact = remesh_detail::exact_solves() - exact0;
  }
  std::sort(t_cons.begin(), t_cons.end());
  std::sort(t_remesh.begin(), t_remesh.end());
  FatSum f0, f1;
  for (const Mesh& m : meshes) f0.add(m);
  for (const Mesh& m : post) f1.add(m);
  std::cout << "| " << what << " | shells | faces | neighbour constraints (s) | remesh (s) | LPs/QPs | exact | fatness | certified |\n"
               "|---|---|---|---|---|---|---|---|---|\n";
  std::printf("| %d | %zu | %zu | %.3f | %.3f | %zu | %zu | %.4f -> %.4f | %s |\n", n, meshes.size(), faces,
              t_cons[t_cons.size() / 2], t_remesh[t_remesh.size() / 2], all, exact, f0.value(), f1.value(),
              certify(post).certified() ? "yes" : "NO");
  return 0;
}

int bench_many_boxes(int n, int repeat) {
  std::mt19937_64 rng(42);
  // 400 boxes in a cube of side 20 (half extents 0.3-2): about 2.5 overlapping pairs per box.
  const double side = 20 * std::cbrt(n / 400.0);
  return bench_synthetic(synthetic::random_boxes(rng, n, side, 0.3, 2.0), "boxes", repeat);
}

int bench_random_cones(int n, int points, int repeat) {
  std::mt19937_64 rng(7);
  // 12 cones in a cube of side 3: most of them overlap one or two others.
  return bench_synthetic(synthetic::random_cones(rng, n, points, 3 * std::cbrt(n / 12.0)),
                         "cones of " + std::to_string(points) + " points", repeat);
}

int main(int argc, char** argv) {
  // Shared data: --data, else $DCSHELL_SHARED_DATA, else ../shared/data (beside the repository).
  const char* env = std::getenv("DCSHELL_SHARED_DATA");
  std::string data = env ? env : "../shared/data", svg_dir, only;
  int iterations = 100, repeat = 3;
  bool hulls_on = true, shells = true, splits = true, flips = true;
  double face_factor = 1;
  int many_boxes = 0, cones = 0, points = 2000;
  std::vector<double> ratios{0.01, 0.1, 1.0, 10.0};
  po::options_description opts("usage: bench_remesh [options]\n\noptions");
  opts.add_options()("help,h", "show this help")("data", po::value(&data), "shared data directory (holds composite/)")(
      "svg-dir", po::value(&svg_dir), "write remesh-<model>.svg plots here")(
      "model", po::value(&only), "only this model")("iterations", po::value(&iterations)->default_value(100), "curve length")(
      "repeat", po::value(&repeat)->default_value(3), "timing runs (median)")(
      "hulls", po::value(&hulls_on)->default_value(true), "hull table and plots")(
      "shells", po::value(&shells)->default_value(true), "shell table (runs the pipeline)")(
      "edge-splits", po::value(&splits)->default_value(true), "lifted edge splits (RemeshOptions::edge_splits)")(
      "edge-flips", po::value(&flips)->default_value(true), "lifted edge flips (RemeshOptions::edge_flips)")(
      "face-factor", po::value(&face_factor)->default_value(1.0),
      "post-only: each shell may have this many times its plain faces (what more faces would buy)")(
      "breakdown", "per model: where the paper pipeline's area and fatness are (stderr)")(
      "many-boxes", po::value(&many_boxes)->default_value(0),
      "only: remesh the plain shells of this many random boxes (timing, exact solves)")(
      "random-cones", po::value(&cones)->default_value(0),
      "only: remesh the plain shells of this many hulls of random points on cones")(
      "points", po::value(&points)->default_value(2000), "points per cone (--random-cones)");
  po::variables_map vm;
  if (!dcshell::bench::parse_options(argc, argv, opts, vm)) return 0;
  if (many_boxes > 0) return bench_many_boxes(many_boxes, repeat);
  if (cones > 0) return bench_random_cones(cones, points, repeat);
  const fs::path root = fs::path(data) / "composite";
  if (!fs::is_directory(root)) {
    std::cerr << "bench_remesh: no " << root << " (shared data absent); nothing to do\n";
    return 0;
  }
  if (!svg_dir.empty()) fs::create_directories(svg_dir);
  std::vector<fs::path> models;
  for (auto& e : fs::directory_iterator(root))
    if (e.is_directory() && (only.empty() || e.path().filename() == only)) models.push_back(e.path());
  std::sort(models.begin(), models.end());

  if (hulls_on) std::cout << "| model | hulls | faces | fatness plain | baseline | ours 10 it, 5% (faces, vol +) | ours at " << iterations
            << " it: 1% | 10% | 100% | 1000% | gain at 5% | time 10 it, 5% (s) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const fs::path& dir : models) {
    if (!hulls_on) break;
    std::vector<std::string> warnings;
    const auto parts = load_parts({dir.string()}, warnings);
    std::vector<Mesh> hulls;
    for (auto& p : parts) {
      Mesh h = convex_hull_mesh(p.points);
      if (!h.is_empty()) hulls.push_back(std::move(h));
    }
    FatSum plain, base;
    std::size_t faces = 0;
    for (auto& h : hulls) {
      plain.add(h);
      base.add(baseline(h));
      faces += h.number_of_faces();
    }
    // The paper's setting, timed.
    std::vector<double> times;
    FatSum paper;
    std::size_t faces_after = 0;
    double v0 = 0, v1 = 0;
    for (int r = 0; r < repeat; ++r) {
      FatSum f;
      std::size_t fa = 0;
      double a = 0, b = 0;
      const auto t0 = std::chrono::steady_clock::now();
      for (auto& h : hulls) {
        RemeshStats st;
        RemeshOptions o;
        o.edge_splits = splits;
        o.edge_flips = flips;
        f.add(remesh_convex_shell(h, std::vector<CutPlane>{}, o, &st));
        fa += st.faces_after;
        a += st.volume_before;
        b += st.volume_after;
      }
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      paper = f, faces_after = fa, v0 = a, v1 = b;
    }
    std::sort(times.begin(), times.end());
    // Curves.
    std::vector<std::vector<double>> curves;
    for (double ratio : ratios) {
      std::vector<FatSum> per(iterations);
      for (auto& h : hulls) {
        RemeshOptions o;
        o.iterations = iterations;
        o.max_volume_increase = ratio;
        o.edge_splits = splits;
        o.edge_flips = flips;
        o.on_iteration = [&](int k, const Mesh& m) { per[k - 1].add(m); };
        remesh_convex_shell(h, std::vector<CutPlane>{}, o);
      }
      std::vector<double> c;
      for (auto& f : per) c.push_back(f.value());
      curves.push_back(c);
    }
    const std::string name = dir.filename().string();
    std::printf("| %s | %zu | %zu | %.4f | %.4f | %.4f (%zu, +%.2f%%) | %.4f | %.4f | %.4f | %.4f | %+.1f%% | %.3f |\n", name.c_str(),
                hulls.size(), faces, plain.value(), base.value(), paper.value(), faces_after, 100 * (v1 / v0 - 1),
                curves[0].back(), curves[1].back(), curves[2].back(), curves[3].back(),
                100 * (paper.value() / plain.value() - 1), times[times.size() / 2]);
    std::fflush(stdout);
    if (!svg_dir.empty())
      write_file_atomically((fs::path(svg_dir) / ("remesh-" + name + ".svg")).string(),
                            [&](std::ostream& os) { os << svg_plot(name, ratios, curves, plain.value(), base.value()); });
  }
  if (!shells) return 0;
  std::cout << "\n| model | shells | faces plain | fatness plain | baseline | paper pipeline (faces, vol +) | gain | post-only (faces, vol +) | gain | time post-only (s) |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const fs::path& dir : models) {
    std::vector<std::string> warnings;
    const auto parts = load_parts({dir.string()}, warnings);
    ShellOptions so;
    so.edge_splits = splits;
    so.edge_flips = flips;
    const ShellResult plain = build_shells(parts, so);
    so.simplify_iterations = 10;
    so.max_volume_increase = 0.05;
    const ShellResult paper = build_shells(parts, so);
    FatSum f0, fb, f1, f2;
    std::size_t n0 = 0, n1 = 0, n2 = 0;
    std::vector<Mesh> meshes;
    for (const auto& s : plain.shells) {
      f0.add(s.mesh);
      fb.add(baseline(s.mesh));
      n0 += s.mesh.number_of_faces();
      meshes.push_back(s.mesh);
    }
    for (const auto& s : paper.shells) f1.add(s.mesh), n1 += s.mesh.number_of_faces();
    if (vm.count("breakdown")) {
      Breakdown b0, b1;
      auto planes = [](const Shell& s) {
        std::vector<CutPlane> p;
        for (const auto& c : s.cuts) p.push_back(c.plane);
        return p;
      };
      for (const auto& s : plain.shells) b0.add(s.mesh, planes(s));
      for (const auto& s : paper.shells) b1.add(s.mesh, planes(s));
      b0.print(dir.filename().string(), "plain");
      b1.print(dir.filename().string(), "paper");
    }
    const std::vector<ShellConstraints> cons = pipeline_constraints(plain, meshes);
    std::vector<double> times;
    std::vector<Mesh> post;
    const std::size_t all0 = remesh_detail::all_solves(), exact0 = remesh_detail::exact_solves();
    for (int r = 0; r < repeat; ++r) {
      post.assign(meshes.size(), Mesh());
      const auto t0 = std::chrono::steady_clock::now();
      // As `dcshell remesh` and the pipeline run it: one shell per core.
      parallel_for(meshes.size(), [&](std::size_t k) {
        RemeshOptions o;
        o.edge_splits = splits;
        o.edge_flips = flips;
        o.max_faces = std::size_t(face_factor * double(meshes[k].number_of_faces()));
        post[k] = remesh_convex_shell(meshes[k], cons[k], o);
      });
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    std::fprintf(stderr, "%s: post-only remesh solved %zu LPs/QPs, %zu of them exactly\n", dir.filename().string().c_str(),
                 remesh_detail::all_solves() - all0, remesh_detail::exact_solves() - exact0);
    double v2 = 0;
    for (const Mesh& m : post) f2.add(m), n2 += m.number_of_faces(), v2 += CGAL::to_double(PMP::volume(m));
    const bool ok = certify(post).certified();
    std::printf("| %s | %zu | %zu | %.4f | %.4f | %.4f (%zu, %+.2f%%) | %+.1f%% | %.4f (%zu, %+.2f%%)%s | %+.1f%% | %.3f |\n",
                dir.filename().string().c_str(), plain.shells.size(), n0, f0.value(), fb.value(), f1.value(), n1,
                100 * (paper.shells_volume / plain.shells_volume - 1), 100 * (f1.value() / f0.value() - 1), f2.value(), n2,
                100 * (v2 / plain.shells_volume - 1), ok ? "" : " NOT CERTIFIED", 100 * (f2.value() / f0.value() - 1),
                times[times.size() / 2]);
    std::fflush(stdout);
  }
  return 0;
}
