// Atomic output: nothing half-written is ever visible, and inputs are never overwritten.
#pragma once
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace dcshell {

/// Writes a file atomically: the content goes to a temporary sibling which is renamed over
/// `path` only after `write` returned and the stream is flushed. Refuses (InputError) a `path`
/// that is one of `inputs` or lies inside an input directory, or is a directory. Throws
/// OutputError, with the system's reason, when it cannot be written (the temporary is removed).
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           const std::vector<std::string>& inputs = {});

/// Throws InputError when writing `path` would overwrite, or write into, one of `inputs`.
void refuse_input_as_output(const std::string& path, const std::vector<std::string>& inputs);

/// What write_file_atomically refuses, checked up front (before the work): an input, a
/// directory, or a file whose directory does not exist.
void check_output_file(const std::string& path, const std::vector<std::string>& inputs);

/// Several files outside an output directory (e.g. the frames of a motion), all or none: each
/// is written to a temporary sibling; commit() renames them all into place; without commit()
/// the temporaries are removed. Same refusals and errors as write_file_atomically.
class AtomicFiles {
 public:
  explicit AtomicFiles(std::vector<std::string> inputs = {}) : inputs_(std::move(inputs)) {}
  ~AtomicFiles();
  AtomicFiles(const AtomicFiles&) = delete;
  AtomicFiles& operator=(const AtomicFiles&) = delete;
  void write(const std::string& path, const std::function<void(std::ostream&)>& write);
  void commit();

 private:
  std::vector<std::string> inputs_;
  std::vector<std::pair<std::string, std::string>> pending_;  // (temporary, target)
};

/// Builds an output directory atomically. Files are written into a temporary sibling
/// directory; commit() renames it to the target. Without commit() (an exception, an early
/// return) the temporary directory is removed and the target is untouched.
/// An existing non-empty target is refused (InputError) unless `force` is set, in which case
/// it is replaced at commit time. Refuses (InputError) a target that is one of `inputs`,
/// contains one of them or lies inside one, so an input is never overwritten. I/O failures
/// throw OutputError.
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
