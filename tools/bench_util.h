// Shared by the tools/bench_* programs: median wall time and the shared data sets.
#pragma once
#include <boost/program_options.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <vector>

namespace dcshell::bench {

/// Parses the command line into vm; prints the options and returns false for --help. A bad
/// option or value: one line on stderr and exit status 2 (not an uncaught exception).
inline bool parse_options(int argc, char** argv, const boost::program_options::options_description& opts,
                          boost::program_options::variables_map& vm) {
  namespace po = boost::program_options;
  try {
    po::store(po::parse_command_line(argc, argv, opts), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    std::cerr << std::filesystem::path(argv[0]).filename().string() << ": " << e.what() << " (--help lists the options)\n";
    std::exit(2);
  }
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return false;
  }
  return true;
}

/// Median wall-clock seconds of `runs` calls of f.
inline double median_seconds(int runs, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// The model folders under data/<sub> for each sub, sorted.
inline std::vector<std::filesystem::path> data_sets(const std::filesystem::path& data, std::initializer_list<const char*> subs) {
  std::vector<std::filesystem::path> sets;
  for (const char* sub : subs)
    if (std::filesystem::is_directory(data / sub))
      for (const auto& e : std::filesystem::directory_iterator(data / sub)) sets.push_back(e.path());
  std::sort(sets.begin(), sets.end());
  return sets;
}

}  // namespace dcshell::bench
