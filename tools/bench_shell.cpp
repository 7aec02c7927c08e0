// Benchmark of the whole `shell` pipeline (hulls -> certified shells, as `dcshell shell` runs it,
// without file output): per shared composite model and bundled example, for every cut method,
// the volume loss, certification and the median wall time over --runs runs.
// Usage: bench_shell [--data DIR] [--examples DIR] [--runs N]
//   DIR defaults to ../shared/data (skipped when absent); examples to ./data.
#include <cstdio>
#include <cstring>

#include "bench_util.h"
#include "dcshell/build_shells.h"
#include "dcshell/error.h"

using namespace dcshell;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::string data = "../shared/data", examples = "data";
  int runs = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--data")) data = argv[i + 1];
    if (!std::strcmp(argv[i], "--examples")) examples = argv[i + 1];
    if (!std::strcmp(argv[i], "--runs")) runs = std::max(1, std::atoi(argv[i + 1]));
  }
  std::vector<fs::path> sets = bench::data_sets(data, {"composite"});
  for (const char* ex : {"bars/bars_45", "three_boxes", "nested", "snowman.obj"})
    if (fs::exists(fs::path(examples) / ex)) sets.push_back(fs::path(examples) / ex);
  std::printf("| model | parts | shells | method | volume loss | certified | median s |\n|---|---|---|---|---|---|---|\n");
  for (const auto& set : sets) {
    std::vector<std::string> warnings;
    std::vector<Part> parts;
    try {
      parts = load_parts({set.string()}, warnings);
    } catch (const InputError& e) {
      std::fprintf(stderr, "bench_shell: error: %s\n", e.what());
      return 2;
    }
    for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full}) {
      ShellOptions opt;
      opt.cut.method = m;
      ShellResult r;
      double t = bench::median_seconds(runs, [&] { r = build_shells(parts, opt); });
      std::printf("| %s | %zu | %zu | %s | %.4f%% | %s | %.2f |\n", set.filename().c_str(), parts.size(), r.shells.size(),
                  to_string(m), 100 * r.volume_loss, r.certification.certified() ? "yes" : "NO", t);
      std::fflush(stdout);
    }
  }
  return 0;
}
