#include "dcshell/atomic_output.h"

#include <unistd.h>

#include <csignal>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "dcshell/error.h"
#include "dcshell/read_mesh.h"

namespace fs = std::filesystem;

namespace dcshell {

namespace {
std::string unique_suffix() { return ".tmp-" + std::to_string(::getpid()); }

bool same_or_inside(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  fs::path a = fs::weakly_canonical(inner, ec), b = fs::weakly_canonical(outer, ec);
  auto ai = a.begin(), bi = b.begin();
  for (; bi != b.end(); ++ai, ++bi)
    if (ai == a.end() || *ai != *bi) return false;
  return true;
}

// Temporary directories alive in this process, removed when SIGINT/SIGTERM/SIGHUP ends it (an
// interrupted run must not leave ".out.tmp-PID" behind). Best effort: the handler uses the
// filesystem library, which is not async-signal-safe, then re-raises with the default action.
constexpr int kMaxTemps = 256;
volatile std::sig_atomic_t temp_count = 0;
char temp_paths[kMaxTemps][1024];

extern "C" void remove_temps_and_reraise(int sig) {
  for (int i = 0; i < temp_count; ++i) {
    std::error_code ec;
    if (temp_paths[i][0]) fs::remove_all(temp_paths[i], ec);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void register_temp(const std::string& path) {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_temps_and_reraise);
    return true;
  }();
  (void)installed;
  for (int i = 0; i < temp_count; ++i)
    if (!temp_paths[i][0]) {
      std::snprintf(temp_paths[i], sizeof temp_paths[i], "%s", path.c_str());
      return;
    }
  if (temp_count < kMaxTemps && path.size() < sizeof temp_paths[0]) {
    std::snprintf(temp_paths[temp_count], sizeof temp_paths[0], "%s", path.c_str());
    temp_count = temp_count + 1;
  }
}

void unregister_temp(const std::string& path) {
  for (int i = 0; i < temp_count; ++i)
    if (path == temp_paths[i]) temp_paths[i][0] = 0;
}

// The system's reason for the last failed stream operation, e.g. " (No space left on device)".
std::string reason() { return errno ? std::string(" (") + std::strerror(errno) + ")" : std::string(); }

void write_stream(const std::string& shown, const std::string& file, const std::function<void(std::ostream&)>& fn) {
  errno = 0;
  std::ofstream os(file, std::ios::binary | std::ios::trunc);
  if (!os) throw OutputError(shown + ": cannot open for writing" + reason());
  fn(os);
  errno = 0;
  os.flush();
  if (!os) throw OutputError(shown + ": write failed" + reason());
  os.close();
  if (!os) throw OutputError(shown + ": write failed" + reason());
}

void rename_or_throw(const fs::path& from, const fs::path& to, const std::string& shown) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) throw OutputError(shown + ": cannot move the finished output into place (" + ec.message() + ")");
}
}  // namespace

void refuse_input_as_output(const std::string& path, const std::vector<std::string>& inputs) {
  // A mesh file written into an input directory would be read as input by the next run.
  const bool mesh = is_mesh_file_name(path);
  std::error_code ec;
  for (const auto& in : inputs) {
    if (same_or_inside(in, path)) throw InputError(path + ": output would overwrite input " + in);
    if (mesh && fs::is_directory(in, ec) && same_or_inside(path, in))
      throw InputError(path + ": output mesh would be written into input directory " + in);
  }
}

void check_output_file(const std::string& path, const std::vector<std::string>& inputs) {
  refuse_input_as_output(path, inputs);
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory, expected a file name");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec)) throw OutputError(path + ": directory " + parent.string() + " does not exist");
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::vector<std::string>& inputs) {
  AtomicFiles files(inputs);
  files.write(path, write);
  files.commit();
}

AtomicFiles::~AtomicFiles() {
  std::error_code ec;
  for (const auto& p : pending_) fs::remove(p.first, ec), unregister_temp(p.first);
}

void AtomicFiles::write(const std::string& path, const std::function<void(std::ostream&)>& fn) {
  check_output_file(path, inputs_);
  pending_.emplace_back(path + unique_suffix(), path);
  register_temp(pending_.back().first);
  write_stream(path, pending_.back().first, fn);
}

void AtomicFiles::commit() {
  for (const auto& [tmp, target] : pending_) rename_or_throw(tmp, target, target), unregister_temp(tmp);
  pending_.clear();
}

AtomicDirectory::AtomicDirectory(const std::string& target, bool force, const std::vector<std::string>& inputs)
    : target_(target), force_(force) {
  if (target.empty()) throw InputError("output directory name is empty");
  refuse_input_as_output(target, inputs);
  std::error_code ec;
  if (fs::exists(target, ec)) {
    if (!fs::is_directory(target, ec)) throw InputError(target + ": exists and is not a directory");
    if (!fs::is_empty(target, ec) && !force_)
      throw InputError(target + ": output directory exists and is not empty (use --force to replace it)");
  }
  fs::path t = fs::absolute(target);
  if (!t.has_filename()) t = t.parent_path();
  temp_ = (t.parent_path() / ("." + t.filename().string() + unique_suffix())).string();
  fs::remove_all(temp_, ec);
  register_temp(temp_);
  if (!fs::create_directories(temp_, ec) || ec)
    throw OutputError(target + ": cannot create output directory (" + ec.message() + ")");
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
  unregister_temp(temp_);
}

std::string AtomicDirectory::path(const std::string& name) const { return (fs::path(temp_) / name).string(); }

void AtomicDirectory::write(const std::string& name, const std::function<void(std::ostream&)>& fn) {
  write_stream(target_ + "/" + name, path(name), fn);
}

void AtomicDirectory::commit() {
  std::error_code ec;
  if (fs::exists(target_, ec)) {
    // Replace: move the old directory aside first so the swap is never half-done.
    std::string old = temp_ + ".old";
    rename_or_throw(target_, old, target_);
    rename_or_throw(temp_, target_, target_);
    fs::remove_all(old, ec);
  } else {
    rename_or_throw(temp_, target_, target_);
  }
  committed_ = true;
}

}  // namespace dcshell
