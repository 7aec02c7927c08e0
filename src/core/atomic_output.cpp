#include "dcshell/atomic_output.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "dcshell/error.h"

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
}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::string tmp = path + unique_suffix();
  try {
    {
      std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
      if (!os) throw std::runtime_error(path + ": cannot open for writing");
      write(os);
      os.flush();
      if (!os) throw std::runtime_error(path + ": write failed");
    }
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

AtomicDirectory::AtomicDirectory(const std::string& target, bool force, const std::vector<std::string>& inputs)
    : target_(target), force_(force) {
  if (target.empty()) throw InputError("output directory name is empty");
  for (const auto& in : inputs)
    if (same_or_inside(in, target))
      throw InputError(target + ": output directory would overwrite input " + in);
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
  if (!fs::create_directories(temp_, ec) || ec)
    throw InputError(target + ": cannot create output directory (" + ec.message() + ")");
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

std::string AtomicDirectory::path(const std::string& name) const { return (fs::path(temp_) / name).string(); }

void AtomicDirectory::write(const std::string& name, const std::function<void(std::ostream&)>& fn) {
  std::ofstream os(path(name), std::ios::binary | std::ios::trunc);
  if (!os) throw std::runtime_error(target_ + "/" + name + ": cannot open for writing");
  fn(os);
  os.flush();
  if (!os) throw std::runtime_error(target_ + "/" + name + ": write failed");
}

void AtomicDirectory::commit() {
  std::error_code ec;
  if (fs::exists(target_, ec)) {
    // Replace: move the old directory aside first so the swap is never half-done.
    std::string old = temp_ + ".old";
    fs::rename(target_, old);
    fs::rename(temp_, target_);
    fs::remove_all(old, ec);
  } else {
    fs::rename(temp_, target_);
  }
  committed_ = true;
}

}  // namespace dcshell
