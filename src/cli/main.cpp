// dcshell command-line entry: dispatches to the registered sub-commands.
#include <boost/program_options.hpp>
#include <algorithm>
#include <cstring>
#include <iostream>

#include "cli/command.h"
#include "dcshell/error.h"

namespace dcshell::cli {

std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}

int guarded(const std::string& cmd, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << "dcshell " << cmd << ": error: " << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "dcshell " << cmd << ": error: " << e.what() << "\n";
    return 2;
  } catch (const boost::program_options::error& e) {
    std::cerr << "dcshell " << cmd << ": error: " << e.what() << " (see 'dcshell " << cmd << " --help')\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "dcshell " << cmd << ": error: out of memory\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "dcshell " << cmd << ": internal error: " << e.what() << "\n";
    return 3;
  }
}

bool parse_command_line(int argc, char** argv, const boost::program_options::options_description& opts,
                        std::vector<std::string>& inputs, boost::program_options::variables_map& vm) {
  namespace po = boost::program_options;
  po::options_description hidden;
  hidden.add_options()("input", po::value(&inputs));
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("input", -1);
  po::store(po::command_line_parser(argc, argv).options(all).positional(pos).run(), vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << opts << "\n";
    return false;
  }
  return true;
}

}  // namespace dcshell::cli

static void usage(std::ostream& os) {
  auto cmds = dcshell::cli::commands();
  std::sort(cmds.begin(), cmds.end(), [](auto& a, auto& b) { return a.name < b.name; });
  os << "usage: dcshell <command> [options]   (dcshell <command> --help for details)\n\ncommands:\n";
  for (auto& c : cmds) os << "  " << c.name << std::string(c.name.size() < 14 ? 14 - c.name.size() : 1, ' ') << c.summary << "\n";
}

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    usage(std::cout);
    return 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "dcshell " << DCSHELL_VERSION << "\n";
    return 0;
  }
  for (auto& c : dcshell::cli::commands())
    if (c.name == argv[1]) return c.run(argc - 1, argv + 1);
  std::cerr << "dcshell: error: unknown command '" << argv[1] << "'\n";
  usage(std::cerr);
  return 2;
}
