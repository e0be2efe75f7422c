// Where tests find the repository, the built binaries and the shared data (../shared).
#pragma once

#include <string>

namespace stairplan::testing {

/// The repository root.
std::string SourceDir();
/// build/bin, where the stairplan CLI is.
std::string BinDir();
/// ../shared beside the repository; empty when it is absent.
std::string SharedDir();
/// SharedDir() + "/" + relative, or "" when ../shared is absent (the caller then SKIPs with WARN).
std::string SharedPath(const std::string& relative);
/// A fresh empty temporary directory for one test.
std::string MakeTempDir(const std::string& tag);
/// Runs a shell command and returns its exit code; stdout and stderr go to the given files.
int RunCommand(const std::string& command, const std::string& out_file, const std::string& err_file);
/// Reads a whole text file ("" when missing).
std::string ReadFile(const std::string& path);

/// What `stairplan ARGS` (this build's program) exited with and printed.
struct StairplanRun {
  int code = -1;
  std::string out, err;
};
/// Runs this build's stairplan with `args`; its stdout and stderr go through files in `dir`.
StairplanRun RunStairplan(const std::string& dir, const std::string& args);

}  // namespace stairplan::testing
