// CLI sub-command registry. Each src/cli/cmd_*.cpp registers itself with a static
// `CommandRegistration`, so sub-commands are independent files.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace boost::program_options {
class options_description;
class variables_map;
}  // namespace boost::program_options

namespace dcshell::cli {

/// A sub-command gets its own arguments (argv[0] is the sub-command name) and returns the
/// process exit code. Exit codes: 0 success/certified, 1 ran but not certified (or failed a
/// quality condition), 2 bad input or usage, or output that cannot be written.
using CommandFn = std::function<int(int argc, char** argv)>;

struct Command {
  std::string name, summary;
  CommandFn run;
};

std::vector<Command>& commands();

struct CommandRegistration {
  CommandRegistration(std::string name, std::string summary, CommandFn fn) {
    commands().push_back({std::move(name), std::move(summary), std::move(fn)});
  }
};

/// Runs `body`, mapping exceptions to exit codes and one-line messages on stderr:
/// InputError, OutputError and boost::program_options errors -> "dcshell <cmd>: error: ..." exit 2;
/// any other exception -> exit 3 (internal error).
int guarded(const std::string& cmd, const std::function<int()>& body);

/// Parses `opts` plus positional inputs into `vm` and `inputs`. Returns false after printing
/// `opts` when --help was given (the command then returns 0).
bool parse_command_line(int argc, char** argv, const boost::program_options::options_description& opts,
                        std::vector<std::string>& inputs, boost::program_options::variables_map& vm);

}  // namespace dcshell::cli
