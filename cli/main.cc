// `stairplan`: dispatches to the sub-commands registered by the *_command.cc files.
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_common.h"
#include "stairplan/version.h"

namespace {

void PrintUsage(std::ostream& out) {
  out << "usage: stairplan <command> [options]   (stairplan <command> --help for details)\n"
      << "       stairplan --version\n\ncommands:\n";
  for (const auto& command : stairplan::cli::Commands()) {
    out << "  " << command.name << std::string(command.name.size() < 14 ? 14 - command.name.size() : 1, ' ')
        << command.summary << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    PrintUsage(std::cerr);
    return stairplan::cli::kExitBadInput;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    PrintUsage(std::cout);
    return stairplan::cli::kExitOk;
  }
  if (name == "--version" || name == "-V") {
    std::cout << "stairplan " << stairplan::kVersion << " (file schema " << stairplan::kSchemaVersion << ")\n";
    return stairplan::cli::kExitOk;
  }
  for (const auto& command : stairplan::cli::Commands()) {
    if (command.name == name) return command.run(std::vector<std::string>(argv + 2, argv + argc));
  }
  std::cerr << "stairplan: unknown command '" << name << "'\n";
  PrintUsage(std::cerr);
  return stairplan::cli::kExitBadInput;
}
