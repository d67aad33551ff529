// Running other programs (sbatch, squeue, weft itself) without a shell: arguments go through as they are.
#pragma once
#include <string>
#include <sys/types.h>
#include <utility>
#include <vector>

namespace weft::farm {

struct ProcessResult {
  int exit_code = -1;   // 127: the program was not found; 128 + N: killed by signal N
  std::string output;   // what it wrote on stdout
  std::string errors;   // and on stderr
};

// Runs argv[0] (looked up on PATH) to completion and captures its output. With timeout_s > 0 a program still
// running then is killed (exit_code 128 + SIGKILL).
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_s = 0);

// Starts argv[0] with stdout and stderr appended to `log` and `env` added to the environment; returns its pid.
pid_t start_process(const std::vector<std::string>& argv, const std::string& log,
                    const std::vector<std::pair<std::string, std::string>>& env = {});

// Waits for any child started by start_process; returns its pid and sets exit_code as run_process does.
pid_t wait_any(int& exit_code);

// True when `program` is an executable file on PATH.
bool on_path(const std::string& program);

}  // namespace weft::farm
