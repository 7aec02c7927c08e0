// Shared by the tools/bench_* programs: median wall time and the shared data sets.
#pragma once
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <vector>

namespace dcshell::bench {

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
