// `dcshell check`: the reference checker. Certifies exactly that every mesh is a closed convex
// polyhedron and that every pair is interior-disjoint; works on any implementation's output.
#include <boost/program_options.hpp>
#include <iostream>

#include "cli/command.h"
#include "cli/report.h"
#include "dcshell/atomic_output.h"
#include "dcshell/certify.h"
#include "dcshell/error.h"
#include "dcshell/read_mesh.h"

namespace po = boost::program_options;

namespace dcshell::cli {
namespace {

int run_check(int argc, char** argv) {
  return guarded("check", [&] {
    po::options_description opts("usage: dcshell check [options] MESH|DIR...\n\n"
                                 "Certifies exactly that every mesh is a closed convex polyhedron and that every pair is\n"
                                 "interior-disjoint (shared faces, edges and points are allowed). Prints a JSON report.\n"
                                 "An OBJ file with several o/g objects counts as one mesh per object.\n"
                                 "Exit status: 0 certified, 1 not certified, 2 bad input.\n\noptions");
    std::vector<std::string> inputs;
    std::string output;
    opts.add_options()("help,h", "show this help")("output,o", po::value(&output), "also write the JSON report to this file")(
        "quiet,q", "print only the JSON report (no problem lines on stderr)");
    po::variables_map vm;
    if (!parse_command_line(argc, argv, opts, inputs, vm)) return 0;
    if (inputs.empty()) throw InputError("no input meshes (see 'dcshell check --help')");
    auto t0 = std::chrono::steady_clock::now();
    // Inputs, as given and expanded, that the report must not overwrite: refused before any work.
    std::vector<std::string> protect = expand_inputs(inputs);
    protect.insert(protect.end(), inputs.begin(), inputs.end());
    if (!output.empty()) check_output_file(output, protect);
    auto set = read_mesh_set(inputs);
    std::vector<std::string> names;
    std::vector<Mesh> meshes;
    for (auto& [n, m] : set) {
      names.push_back(n);
      meshes.push_back(std::move(m));
    }
    CertificationReport rep = certify(meshes);
    double secs = seconds_since(t0);
    auto write = [&](std::ostream& os) {
      JsonWriter json(os);
      json.begin_object();
      json.field("tool", "dcshell check");
      write_certification(json, rep, names);
      json.field("time_s", secs);
      json.end_object();
    };
    if (!output.empty()) write_file_atomically(output, write, protect);
    write(std::cout);
    if (!vm.count("quiet")) {
      print_certification_problems(rep, names);
      std::cerr << (rep.certified() ? "certified: " : "NOT certified: ") << meshes.size() << " meshes, "
                << rep.overlaps.size() << " overlapping pairs\n";
    }
    return rep.certified() ? 0 : 1;
  });
}

const CommandRegistration reg("check", "certify meshes as convex and pairwise interior-disjoint (exact)", run_check);

}  // namespace
}  // namespace dcshell::cli
