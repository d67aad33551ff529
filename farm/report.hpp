// What a batch has done: each task's state and frames while it runs (`weft batch status`), and once it has
// run, a summary with figures and a contact sheet per task (`weft batch collect`).
#pragma once
#include "backends/backend.hpp"
#include "farm/batch.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace weft::farm {

struct TaskStatus {
  std::string state;       // pending, running, ... (the queue's), done, failed, stopped, incomplete, not started
  int frames_done = 0;     // stored in the cache, its initial state included
  int frames_planned = 0;  // 0 while the cache does not exist
  int exit_code = -1;      // of the last run that ended; -1: none has
};

// The queue's states (slurm_states; empty for a local batch or one that has left the queue) and the caches.
std::vector<TaskStatus> batch_status(const Batch& b, const std::map<int, std::string>& queue);

struct TaskSummary {
  TaskStatus status;
  double ms_per_frame = 0;      // mean wall time of the computed frames
  double max_strain = 0;        // over every stored frame
  double p99_strain = 0;        // at the last frame
  long intersections = -1;      // at the last frame; -1: no cache
  uint64_t hash = 0;            // of every stored frame, as `weft run --hash` prints it
  bool sheet = false;           // Task::sheet() was written
};

// Reads every task's cache, counts intersections and measures strain at its last frame on backend `b`, draws
// its contact sheet (unless `sheets` is false), and writes <output>/summary.md and <output>/summary.html.
std::vector<TaskSummary> collect(const Batch& b, Backend backend, bool sheets);

std::string hash_text(uint64_t h);

}  // namespace weft::farm
