// A batch: the shots and wedges a department runs on a farm, read from a JSON description (docs/farm.md) and
// expanded into tasks, each one `weft run ... -o <task>/cache.h5 --resume` with its own output folder.
#pragma once
#include "io/scene_overrides.hpp"

#include <string>
#include <vector>

namespace weft::farm {

struct Task {
  std::string name;    // unique in the batch; its folder's name
  std::string scene;   // builtin:NAME or an absolute path
  int res = 0;         // of a built-in scene; 0: its default
  std::string frames;  // "A-B"; "": the scene's
  std::vector<io::SceneOverride> set;    // the task's settings, then its wedge values
  std::vector<io::SceneOverride> wedge;  // the wedge values alone ("" wedge: a single task)
  std::string wedge_name;                // the task entry a wedge task came from
  std::string dir;                       // absolute output folder

  std::string cache() const { return dir + "/cache.h5"; }
  std::string log() const { return dir + "/log.txt"; }
  std::string exit_file() const { return dir + "/exit_code"; }  // the run's exit status, once it has ended
  std::string sheet() const { return dir + "/sheet.png"; }
};

struct SlurmOptions {
  std::string partition;               // "": the cluster's default
  std::string time;                    // per task, sbatch --time ("": the partition's limit)
  int gpus_per_task = 0, cpus_per_task = 0;
  int max_parallel = 0;                // array tasks running at once (--array=0-N%M); 0: no limit
  std::vector<std::string> sbatch_args;  // passed to sbatch as they are
};

struct Batch {
  std::string file;        // the description, as given
  std::string name;        // "name", or the file's stem
  std::string output;      // absolute folder holding the tasks' folders and the batch's own files
  std::string backend;     // weft --backend for every task ("": weft's default)
  int threads = 0;         // weft --threads (0: Kokkos' default)
  std::string executable;  // the weft every task runs (absolute)
  std::vector<Task> tasks;
  SlurmOptions slurm;

  std::string submission_file() const { return output + "/submission.json"; }
};

// Reads and expands a batch description. Every setting name and value is checked (io::check_override), task
// names are unique, scene files exist. Bad input throws InputError naming the file and the task
// ("wedge.json: tasks[1] (sheet-friction): wedge.frction: unknown setting ..."). `executable`: the weft
// tasks run unless the description names one.
Batch read_batch(const std::string& path, const std::string& executable);

// The command line of a task: weft [--backend B] [--threads N] run SCENE ... -o CACHE --resume.
std::vector<std::string> task_command(const Batch& b, const Task& t);

// Why the task's existing cache cannot be continued by it ("" when there is none, or it can): the cache of
// another scene or other settings. Loads the task's scene.
std::string cache_conflict(const Task& t);

// A word for a POSIX shell: quoted unless it is plain.
std::string shell_quote(const std::string& word);
std::string shell_line(const std::vector<std::string>& words);

// What was submitted, kept in Batch::submission_file(): the scheduler, its job id (Slurm), the time.
struct Submission {
  std::string scheduler;  // "slurm" | "local"
  std::string job;        // Slurm's job id of the array
  std::string script;     // the job script
  std::string time;       // ISO 8601, UTC
};
void write_submission(const Batch& b, const Submission& s);
std::string utc_now();  // for Submission::time
bool read_submission(const Batch& b, Submission& s);  // false when nothing was submitted

}  // namespace weft::farm
