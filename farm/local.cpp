#include "farm/process.hpp"
#include "farm/scheduler.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace weft::farm {
namespace {

volatile std::sig_atomic_t stop_requested = 0;
void request_stop(int) { stop_requested = 1; }

// While tasks run, SIGINT / SIGTERM only stop new ones from starting: the running weft processes get the
// signal too (the same process group) and end with complete caches.
class DeferSignals {
 public:
  DeferSignals() {
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~DeferSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::app);
  out << text;
}

}  // namespace

int run_local(const Batch& b, int parallel, int gpus) {
  namespace fs = std::filesystem;
  if (gpus > 0) parallel = gpus;
  parallel = std::max(parallel, 1);
  fs::create_directories(b.output);
  write_submission(b, {"local", "", "", utc_now()});
  const DeferSignals defer;
  std::map<pid_t, std::pair<size_t, int>> running;  // pid -> (task, slot)
  std::vector<int> free_slots;
  for (int s = parallel - 1; s >= 0; --s) free_slots.push_back(s);
  size_t next = 0, ended = 0;
  int failed = 0;
  while (ended < next || (next < b.tasks.size() && !stop_requested)) {
    while (next < b.tasks.size() && !free_slots.empty() && !stop_requested) {
      const Task& t = b.tasks[next];
      fs::create_directories(t.dir);
      fs::remove(t.exit_file());
      const int slot = free_slots.back();
      free_slots.pop_back();
      write_text(t.log(), "== " + utc_now() + " task " + std::to_string(next) + " on this machine (weft batch, local)\n");
      std::vector<std::pair<std::string, std::string>> env;
      if (gpus > 0) env.emplace_back("CUDA_VISIBLE_DEVICES", std::to_string(slot));
      const pid_t pid = start_process(task_command(b, t), t.log(), env);
      running[pid] = {next, slot};
      std::printf("task %s: started (%zu of %zu)\n", t.name.c_str(), next + 1, b.tasks.size());
      std::fflush(stdout);
      ++next;
    }
    int code = 0;
    const pid_t pid = wait_any(code);
    if (pid < 0) break;
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Task& t = b.tasks[it->second.first];
    free_slots.push_back(it->second.second);
    running.erase(it);
    ++ended;
    {
      std::ofstream out(t.exit_file());
      out << code << "\n";
    }
    if (code != 0) ++failed;
    std::printf("task %s: %s (exit %d; log %s)\n", t.name.c_str(), code == 0 ? "done" : "failed", code,
                t.log().c_str());
    std::fflush(stdout);
  }
  if (stop_requested && next < b.tasks.size())
    std::printf("stopped: %zu of %zu tasks not started; submit again to continue\n", b.tasks.size() - next,
                b.tasks.size());
  return failed + int(b.tasks.size() - next);
}

}  // namespace weft::farm
