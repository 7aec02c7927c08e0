// Atomic output: nothing half-written is ever visible, and inputs are never overwritten.
#pragma once
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace dcshell {

/// Writes a file atomically: the content goes to a temporary sibling which is renamed over
/// `path` only after `write` returned and the stream is flushed. Throws std::runtime_error on
/// I/O failure (the temporary is removed).
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Builds an output directory atomically. Files are written into a temporary sibling
/// directory; commit() renames it to the target. Without commit() (an exception, an early
/// return) the temporary directory is removed and the target is untouched.
/// An existing non-empty target is refused (InputError) unless `force` is set, in which case
/// it is replaced at commit time. Refuses (InputError) a target that is one of `inputs` or
/// contains one of them, so an input is never overwritten.
class AtomicDirectory {
 public:
  AtomicDirectory(const std::string& target, bool force, const std::vector<std::string>& inputs = {});
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  /// Path of `name` inside the temporary directory.
  std::string path(const std::string& name) const;
  void write(const std::string& name, const std::function<void(std::ostream&)>& write);
  void commit();
  const std::string& target() const { return target_; }

 private:
  std::string target_, temp_;
  bool force_, committed_ = false;
};

}  // namespace dcshell
