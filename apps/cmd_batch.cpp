// `weft batch plan|submit|status|collect BATCH.json`: shots and wedges as one batch (docs/farm.md). plan
// prints the tasks and their output folders; submit runs them on Slurm as one job array, or on this machine;
// status shows each task's state and frames; collect writes the summary with a contact sheet per task.
#include "apps/cli.hpp"
#include "core/error.hpp"
#include "farm/report.hpp"
#include "farm/scheduler.hpp"

#include <unistd.h>

#include <climits>
#include <cstdio>
#include <string>

namespace weft::cli {
namespace {

struct BatchOptions {
  std::string file, scheduler = "slurm";
  int parallel = 1, gpus = 0;
  bool commands = false, no_sheets = false;
};

std::string this_executable() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw Error("cannot find the weft executable (/proc/self/exe)");
  return std::string(buf, size_t(n));
}

farm::Batch read(const BatchOptions& o) {
  try {
    return farm::read_batch(o.file, this_executable());
  } catch (const InputError& e) {
    throw Error(e.what(), 2);
  }
}

std::string pad(std::string s, size_t width) {
  if (s.size() < width) s.resize(width, ' ');
  return s;
}

std::string settings_text(const farm::Task& t) {
  std::string s;
  for (const auto& o : t.set) s += (s.empty() ? "" : " ") + o.name + "=" + o.value;
  return s.empty() ? "-" : s;
}

std::string scene_text(const farm::Task& t) {
  return t.scene + (t.res > 0 ? " --res " + std::to_string(t.res) : "");
}

int plan(const BatchOptions& o) {
  const farm::Batch b = read(o);
  std::printf("batch %s: %zu tasks, output %s\n", b.name.c_str(), b.tasks.size(), b.output.c_str());
  size_t wn = 4, ws = 5, wf = 6;
  for (const auto& t : b.tasks) {
    wn = std::max(wn, t.name.size());
    ws = std::max(ws, scene_text(t).size());
    wf = std::max(wf, t.frames.size());
  }
  std::printf("  %s  %s  %s  %s\n", pad("task", wn).c_str(), pad("scene", ws).c_str(), pad("frames", wf).c_str(),
              "settings");
  for (const auto& t : b.tasks)
    std::printf("  %s  %s  %s  %s\n", pad(t.name, wn).c_str(), pad(scene_text(t), ws).c_str(),
                pad(t.frames.empty() ? "scene" : t.frames, wf).c_str(), settings_text(t).c_str());
  std::printf("each task writes <output>/<task>/cache.h5, log.txt and exit_code; collect adds sheet.png and "
              "<output>/summary.md, summary.html\n");
  if (o.commands)
    for (const auto& t : b.tasks) std::printf("%s\n", farm::shell_line(farm::task_command(b, t)).c_str());
  return 0;
}

int submit(const GlobalOptions& g, const BatchOptions& o) {
  const farm::Batch b = read(o);
  // A cache of another scene or other settings would be refused by the task itself, on the farm: refuse the
  // batch now, before anything is submitted.
  std::string conflicts;
  for (const auto& t : b.tasks) {
    const std::string why = farm::cache_conflict(t);
    if (!why.empty()) conflicts += "\n  task " + t.name + ": " + why;
  }
  if (!conflicts.empty())
    throw Error(b.file + ": nothing submitted; remove or move these caches, or rename the tasks:" + conflicts, 2);
  if (o.scheduler == "local") {
    if (o.gpus > 0 && resolve_backend(g) != Backend::Cuda && b.backend != "cuda")
      throw Error("--gpus runs tasks on GPUs: give the batch \"backend\": \"cuda\"", 2);
    std::printf("batch %s: %zu tasks on this machine, %d at a time; output %s\n", b.name.c_str(), b.tasks.size(),
                o.gpus > 0 ? o.gpus : o.parallel, b.output.c_str());
    const int failed = farm::run_local(b, o.parallel, o.gpus);
    std::printf("%zu tasks, %d not done; weft batch collect %s writes the summary\n", b.tasks.size(), failed,
                b.file.c_str());
    return failed == 0 ? 0 : 1;
  }
  farm::Submission previous;
  if (farm::read_submission(b, previous) && previous.scheduler == "slurm" && !previous.job.empty()) {
    std::map<int, std::string> queued;
    try {
      queued = farm::slurm_states(previous.job);
    } catch (const farm::SchedulerError& e) {
      throw Error(std::string(e.what()) + "; nothing submitted", 3);
    }
    size_t active = 0;
    for (const auto& [task, state] : queued) active += farm::slurm_active(state);
    if (active > 0)
      throw Error("job " + previous.job + " of this batch is still in the queue (" + std::to_string(active) +
                      " tasks): two runs would write the same caches; wait for it or scancel it. Nothing submitted", 2);
  }
  try {
    const farm::Submission s = farm::submit_slurm(b);
    std::printf("submitted job %s: %zu array tasks (script %s)\nweft batch status %s shows their progress\n",
                s.job.c_str(), b.tasks.size(), s.script.c_str(), b.file.c_str());
  } catch (const farm::SchedulerError& e) {
    throw Error(std::string(e.what()) + "; nothing submitted", 3);
  }
  return 0;
}

int status(const BatchOptions& o) {
  const farm::Batch b = read(o);
  farm::Submission s;
  std::map<int, std::string> queue;
  if (!farm::read_submission(b, s)) {
    std::printf("batch %s: not submitted yet\n", b.name.c_str());
  } else if (s.scheduler == "slurm") {
    try {
      queue = farm::slurm_states(s.job);
    } catch (const farm::SchedulerError& e) {
      std::fprintf(stderr, "weft: warning: %s; the states below come from the caches only\n", e.what());
    }
    std::printf("batch %s: Slurm job %s, submitted %s\n", b.name.c_str(), s.job.c_str(), s.time.c_str());
  } else {
    std::printf("batch %s: run on this machine, started %s\n", b.name.c_str(), s.time.c_str());
  }
  const auto st = farm::batch_status(b, queue);
  size_t wn = 4;
  for (const auto& t : b.tasks) wn = std::max(wn, t.name.size());
  std::printf("  %s  %-12s  %9s  %s\n", pad("task", wn).c_str(), "state", "frames", "exit");
  int done = 0;
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const std::string frames =
        std::to_string(st[k].frames_done) + "/" + (st[k].frames_planned > 0 ? std::to_string(st[k].frames_planned) : "?");
    std::printf("  %s  %-12s  %9s  %s\n", pad(b.tasks[k].name, wn).c_str(), st[k].state.c_str(), frames.c_str(),
                st[k].exit_code >= 0 ? std::to_string(st[k].exit_code).c_str() : "-");
    done += st[k].state == "done";
  }
  std::printf("%d of %zu tasks done\n", done, b.tasks.size());
  return 0;
}

int collect(const GlobalOptions& g, const BatchOptions& o) {
  const farm::Batch b = read(o);
  const Backend backend = resolve_backend(g);
  Runtime rt(g.threads);
  const auto summary = farm::collect(b, backend, !o.no_sheets);
  int done = 0;
  for (const auto& s : summary) done += s.status.state == "done";
  std::printf("batch %s: %d of %zu tasks done\n", b.name.c_str(), done, b.tasks.size());
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const auto& s = summary[k];
    std::printf("  %-24s %-11s frames %d/%d", b.tasks[k].name.c_str(), s.status.state.c_str(), s.status.frames_done,
                s.status.frames_planned);
    if (s.status.frames_done > 0)
      std::printf("  %.1f ms/frame  max strain %.3f  p99 %.3f  intersections %ld  hash %s", s.ms_per_frame,
                  s.max_strain, s.p99_strain, s.intersections, farm::hash_text(s.hash).c_str());
    std::printf("\n");
  }
  std::printf("wrote %s/summary.md and %s/summary.html\n", b.output.c_str(), b.output.c_str());
  return 0;
}

void add_batch(CLI::App& app, const GlobalOptions& g, Action& action) {
  auto o = std::make_shared<BatchOptions>();
  auto* cmd = app.add_subcommand("batch", "shots and wedges as one batch, on Slurm or this machine (docs/farm.md)");
  cmd->require_subcommand(1);
  auto* p = cmd->add_subcommand("plan", "expand a batch description and print its tasks and output folders");
  p->add_option("batch", o->file, "the batch description (.json)")->required();
  p->add_flag("--commands", o->commands, "also print each task's weft command line");
  p->callback([&action, o] { action = [o] { return plan(*o); }; });
  auto* s = cmd->add_subcommand("submit", "run the batch: one Slurm job array, or on this machine");
  s->add_option("batch", o->file, "the batch description (.json)")->required();
  s->add_option("--scheduler", o->scheduler, "slurm (sbatch --array) | local (this machine)")
      ->capture_default_str()
      ->check(CLI::IsMember({"slurm", "local"}));
  s->add_option("--parallel", o->parallel, "local: tasks at once")->capture_default_str()->check(CLI::PositiveNumber);
  s->add_option("--gpus", o->gpus, "local: one task per GPU, on this many GPUs (CUDA_VISIBLE_DEVICES)")
      ->check(CLI::NonNegativeNumber);
  s->callback([&g, &action, o] { action = [&g, o] { return submit(g, *o); }; });
  auto* st = cmd->add_subcommand("status", "each task's state (the queue's and its cache's) and frames done");
  st->add_option("batch", o->file, "the batch description (.json)")->required();
  st->callback([&action, o] { action = [o] { return status(*o); }; });
  auto* c = cmd->add_subcommand("collect", "write <output>/summary.md and summary.html with a contact sheet per task");
  c->add_option("batch", o->file, "the batch description (.json)")->required();
  c->add_flag("--no-sheets", o->no_sheets, "skip the contact sheets");
  c->callback([&g, &action, o] { action = [&g, o] { return collect(g, *o); }; });
}

const Register reg("batch", add_batch);

}  // namespace
}  // namespace weft::cli
