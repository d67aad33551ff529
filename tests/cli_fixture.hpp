// The weft binary, as the cli_* topics run it: `weft --backend serial <args>` with its output kept. A test
// that needs it skips when the binary is not built (a build of some targets only).
#pragma once
#include "tests/scratch_dir_fixture.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace weft::test {

class Cli {
 public:
  explicit Cli(const ScratchDir& dir) : dir_(dir) {}
  static std::string binary() { return std::string(WEFT_BIN_DIR) + "/weft"; }
  static bool available() { return std::filesystem::exists(binary()); }
  // Runs `weft --backend serial <args>`, `env` (VAR=VALUE ...) set for it; keeps its output (stdout and
  // stderr) in `output` and leaves no file behind; returns its exit status.
  int operator()(const std::string& args, const std::string& env = "") {
    const std::string log = dir_.file("weft.log");
    const std::string command = env + " " + binary() + " --backend serial " + args + " > '" + log + "' 2>&1";
    const int status = std::system(command.c_str());
    output = dir_.read("weft.log");
    std::filesystem::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  // The 16 hex digits of the last "hash" line (weft run --hash); a test failure when there is none.
  std::string hash() const {
    const size_t at = output.rfind("hash ");
    if (at == std::string::npos) ADD_FAILURE() << "no hash line in:\n" << output;
    return at == std::string::npos ? "" : output.substr(at + 5, 16);
  }
  std::string output;

 private:
  const ScratchDir& dir_;
};

// A small run the cli_* topics share: the hanging sheet in few substeps and iterations.
inline const std::string kSheet = "run builtin:hanging-sheet --res 5 --substeps 4 --iterations 8";

}  // namespace weft::test

#define WEFT_NEED_CLI() \
  if (!weft::test::Cli::available()) GTEST_SKIP() << weft::test::Cli::binary() << " is not built"
