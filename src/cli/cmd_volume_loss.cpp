// `dcshell volume-loss`: the paper's quality metric, computed exactly:
// (vol(∪ hulls of the parts) − Σ vol(shells)) / vol(∪ hulls of the parts).
#include <boost/program_options.hpp>
#include <iostream>

#include "cli/command.h"
#include "cli/report.h"
#include "dcshell/certify.h"
#include "dcshell/error.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/load_parts.h"
#include "dcshell/read_mesh.h"
#include "dcshell/volume_loss.h"

namespace po = boost::program_options;

namespace dcshell::cli {
namespace {

int run_volume_loss(int argc, char** argv) {
  return guarded("volume-loss", [&] {
    po::options_description opts(
        "usage: dcshell volume-loss --parts INPUT... --shells MESH|DIR...\n\n"
        "Exact volume loss of a set of shells against the composite shape they came from:\n"
        "(vol(union of the parts' convex hulls) - sum of shell volumes) / vol(union).\n"
        "Parts are read as everywhere in dcshell: several files = one part each; one file = its\n"
        "OBJ groups or its connected components. Also certifies the shells (as 'dcshell check').\n"
        "Exit status: 0 shells certified, 1 not certified, 2 bad input.\n\noptions");
    std::vector<std::string> parts_in, shells_in;
    opts.add_options()("help,h", "show this help")("parts,p", po::value(&parts_in)->multitoken(), "composite shape")(
        "shells,s", po::value(&shells_in)->multitoken(), "shell meshes or directories")(
        "quiet,q", "no warnings or problem lines on stderr");
    po::variables_map vm;
    po::store(po::command_line_parser(argc, argv).options(opts).run(), vm);
    po::notify(vm);
    if (vm.count("help")) {
      std::cout << opts << "\n";
      return 0;
    }
    if (parts_in.empty()) throw InputError("missing --parts");
    if (shells_in.empty()) throw InputError("missing --shells");
    const bool quiet = vm.count("quiet");
    auto t0 = std::chrono::steady_clock::now();
    std::vector<std::string> warnings;
    std::vector<Part> parts = load_parts(parts_in, warnings);
    if (!quiet)
      for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
    auto set = read_mesh_set(shells_in);
    std::vector<std::string> names;
    std::vector<Mesh> shells;
    for (auto& [n, m] : set) {
      names.push_back(n);
      shells.push_back(std::move(m));
    }
    std::vector<ExactPolytope> hulls;
    for (std::size_t i = 0; i < parts.size(); ++i) hulls.push_back(exact_hull(parts[i].points, int(i)));
    CertificationReport rep = certify(shells);
    // The metric is defined on closed, outward shells; the others are reported as not certified.
    std::vector<Mesh> closed;
    for (std::size_t k = 0; k < shells.size(); ++k)
      if (rep.meshes[k].closed && rep.meshes[k].outward) closed.push_back(shells[k]);
    const VolumeLoss loss = volume_loss(hulls, closed);
    JsonWriter json(std::cout);
    json.begin_object()
        .field("tool", "dcshell volume-loss")
        .field("parts", parts.size())
        .field("shells", shells.size())
        .field("union_volume", loss.union_volume)
        .field("shells_volume", loss.shells_volume)
        .field("volume_loss", loss.value)
        .field("volume_loss_error_bound", loss.error_bound)
        .field("volume_loss_exact", loss.exact)
        .field("union_volume_error_bound", loss.union_stats.error_bound)
        .field("union_exact_fallback", loss.union_stats.exact_fallback)
        .field("union_fixed_point", loss.union_stats.fixed_point)
        .field("union_method", to_string(loss.union_stats.method))
        .field("union_terms", loss.union_stats.terms)
        .field("union_nerve_polytopes", loss.union_stats.nerve_polytopes)
        .field("max_overlap_depth", loss.union_stats.max_clique);
    write_certification(json, rep, names);
    json.field("time_s", seconds_since(t0));
    json.end_object();
    if (!quiet) print_certification_problems(rep, names);
    return rep.certified() ? 0 : 1;
  });
}

const CommandRegistration reg("volume-loss", "exact volume loss of shells against their composite shape", run_volume_loss);

}  // namespace
}  // namespace dcshell::cli
