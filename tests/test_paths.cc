#include "test_paths.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace stairplan::testing {

std::string SourceDir() { return STAIRPLAN_SOURCE_DIR; }
std::string BinDir() { return STAIRPLAN_BIN_DIR; }

std::string SharedDir() {
  const std::filesystem::path shared(STAIRPLAN_SHARED_DIR);
  return std::filesystem::is_directory(shared) ? std::filesystem::canonical(shared).string() : std::string();
}

std::string SharedPath(const std::string& relative) {
  const std::string dir = SharedDir();
  return dir.empty() ? std::string() : dir + "/" + relative;
}

std::string MakeTempDir(const std::string& tag) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("stairplan-" + tag + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed for " + pattern);
  return pattern;
}

namespace {

// Under the sanitizers the programs a test starts (the CLI, end to end) run without ASan's fake
// stacks, as the end-to-end test programs do (cmake/Sanitizers.cmake): they cost the CLI a tenth
// of its CPU time on a QP plan, and the unit programs, running the same functions in process, keep
// the check.
// ASan reads ASAN_OPTIONS when a process starts, so this reaches the children only.
void ChildrenWithoutFakeStacks() {
#ifdef STAIRPLAN_SANITIZED
  static const bool done = [] {
    const char* options = std::getenv("ASAN_OPTIONS");
    const std::string appended = std::string(options ? options : "") + ":detect_stack_use_after_return=0";
    return setenv("ASAN_OPTIONS", appended.c_str(), 1) == 0;
  }();
  (void)done;
#endif
}

}  // namespace

int RunCommand(const std::string& command, const std::string& out_file, const std::string& err_file) {
  ChildrenWithoutFakeStacks();
  const std::string full = command + " >" + out_file + " 2>" + err_file + " </dev/null";
  const int raw = std::system(full.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

StairplanRun RunStairplan(const std::string& dir, const std::string& args) {
  StairplanRun run;
  run.code = RunCommand(BinDir() + "/stairplan " + args, dir + "/stairplan.out", dir + "/stairplan.err");
  run.out = ReadFile(dir + "/stairplan.out");
  run.err = ReadFile(dir + "/stairplan.err");
  return run;
}

}  // namespace stairplan::testing
