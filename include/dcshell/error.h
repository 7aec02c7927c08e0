// Error type for bad input. The CLI prints what() on one line and exits with code 2.
#pragma once
#include <stdexcept>
#include <string>

namespace dcshell {

/// Bad input: the message names the file (and line when known) and the problem,
/// e.g. "parts/a.obj:12: face index 40 out of range (30 vertices)".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Output that cannot be written (a missing or read-only directory, a full disk, a target that
/// is a directory). The CLI treats it like bad usage: one line, exit code 2.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats "file:line: what" (line omitted when 0).
std::string input_error_message(const std::string& file, std::size_t line, const std::string& what);

}  // namespace dcshell
