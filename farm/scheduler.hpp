// Where a batch's tasks run: Slurm (one job array, `sbatch --array`), or this machine (`--scheduler local`).
#pragma once
#include "farm/batch.hpp"

#include <map>
#include <stdexcept>
#include <string>

namespace weft::farm {

// The scheduler cannot be reached or refused the job; nothing was submitted.
struct SchedulerError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The job script: #SBATCH lines from the batch's "slurm" options, then one case per array index that runs
// the task's command (task_command) with its output appended to the task's log and its exit status kept in
// the task's exit_code file. Requeued tasks (--requeue) continue their caches (--resume).
std::string slurm_script(const Batch& b);

// Checks that the controller answers, writes the script to <output>/slurm/array.sh and submits it with
// `sbatch --parsable`; returns the job id. Throws SchedulerError with sbatch's own words.
Submission submit_slurm(const Batch& b);

// The queue's view of the array: array index -> state (PENDING, RUNNING, COMPLETED, FAILED, ...), from
// `squeue -r -t all`, and from `sacct` for tasks the controller has forgotten (MinJobAge after they ended)
// where accounting is kept; otherwise those are absent. Throws SchedulerError when squeue fails.
std::map<int, std::string> slurm_states(const std::string& job);
// A state of a task that has not ended yet (PENDING, RUNNING, COMPLETING, REQUEUED, SUSPENDED, ...).
bool slurm_active(const std::string& state);

// Runs the tasks on this machine, `parallel` at a time (each with CUDA_VISIBLE_DEVICES set to its slot when
// `gpus` > 0), printing a line as each ends; SIGINT / SIGTERM stop starting tasks and wait for the running
// ones, which end with complete caches. Returns the number of tasks that failed.
int run_local(const Batch& b, int parallel, int gpus);

}  // namespace weft::farm
