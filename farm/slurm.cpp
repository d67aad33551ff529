#include "farm/process.hpp"
#include "farm/scheduler.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace weft::farm {
namespace {

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
  return s;
}

std::string first_line(const std::string& s) {
  const std::string t = trimmed(s);
  const size_t nl = t.find('\n');
  return nl == std::string::npos ? t : t.substr(0, nl);
}

}  // namespace

std::string slurm_script(const Batch& b) {
  const SlurmOptions& s = b.slurm;
  std::ostringstream o;
  o << "#!/bin/bash\n"
    << "# weft batch " << b.name << ": " << b.tasks.size() << " tasks as one Slurm job array.\n"
    << "# Written by `weft batch submit " << b.file << " --scheduler slurm` (docs/farm.md). Each task continues its\n"
    << "# cache (--resume), so a preempted or requeued task goes on from its last complete frame.\n"
    << "#SBATCH --job-name=weft-" << b.name << "\n"
    << "#SBATCH --array=0-" << b.tasks.size() - 1 << (s.max_parallel > 0 ? "%" + std::to_string(s.max_parallel) : "")
    << "\n"
    << "#SBATCH --output=" << b.output << "/slurm/%A_%a.out\n"
    << "#SBATCH --open-mode=append\n"
    << "#SBATCH --requeue\n";
  if (!s.partition.empty()) o << "#SBATCH --partition=" << s.partition << "\n";
  if (!s.time.empty()) o << "#SBATCH --time=" << s.time << "\n";
  if (s.cpus_per_task > 0) o << "#SBATCH --cpus-per-task=" << s.cpus_per_task << "\n";
  if (s.gpus_per_task > 0) o << "#SBATCH --gres=gpu:" << s.gpus_per_task << "\n";
  for (const std::string& a : s.sbatch_args) o << "#SBATCH " << a << "\n";
  o << "set -u\n"
    << "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const Task& t = b.tasks[k];
    o << "  " << k << ") dir=" << shell_quote(t.dir) << "\n"
      << "     cmd=(" << shell_line(task_command(b, t)) << ") ;;\n";
  }
  o << "  *) echo \"weft batch: no task $SLURM_ARRAY_TASK_ID\" >&2; exit 2 ;;\n"
    << "esac\n"
    << "mkdir -p \"$dir\" && rm -f \"$dir/exit_code\"\n"
    << "echo \"== $(date -u +%Y-%m-%dT%H:%M:%SZ) job ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID} on $(hostname),"
       " restart ${SLURM_RESTART_COUNT:-0}\" >> \"$dir/log.txt\"\n"
    << "\"${cmd[@]}\" >> \"$dir/log.txt\" 2>&1\n"
    << "rc=$?\n"
    << "echo \"$rc\" > \"$dir/exit_code\"\n"
    << "exit \"$rc\"\n";
  return o.str();
}

Submission submit_slurm(const Batch& b) {
  for (const char* tool : {"sbatch", "sinfo"})
    if (!on_path(tool))
      throw SchedulerError(std::string("slurm: ") + tool + " is not on PATH (install Slurm's client commands, or "
                           "use --scheduler local)");
  const double patience = 20;
  const ProcessResult ping = run_process({"sinfo", "-h", "-o", "%P"}, patience);
  if (ping.exit_code != 0)
    throw SchedulerError("slurm: the controller does not answer (sinfo: " +
                         (ping.exit_code == 128 + 9 ? "no answer in " + std::to_string(int(patience)) + " s"
                                                    : first_line(ping.errors + ping.output)) + ")");
  namespace fs = std::filesystem;
  fs::create_directories(b.output + "/slurm");
  for (const Task& t : b.tasks) fs::create_directories(t.dir);
  Submission sub{"slurm", "", b.output + "/slurm/array.sh", utc_now()};
  {
    std::ofstream out(sub.script);
    out << slurm_script(b);
    if (!out) throw SchedulerError(sub.script + ": cannot write");
  }
  fs::permissions(sub.script, fs::perms::owner_exec, fs::perm_options::add);
  const ProcessResult r = run_process({"sbatch", "--parsable", sub.script});
  if (r.exit_code != 0) throw SchedulerError("slurm: sbatch refused the job: " + trimmed(r.errors + r.output));
  sub.job = first_line(r.output);
  const size_t semi = sub.job.find(';');  // "jobid;cluster" on a federation
  if (semi != std::string::npos) sub.job.resize(semi);
  if (sub.job.empty()) throw SchedulerError("slurm: sbatch printed no job id");
  write_submission(b, sub);
  return sub;
}

std::map<int, std::string> slurm_states(const std::string& job) {
  // -t all: finished tasks too, while the controller remembers them (MinJobAge).
  const ProcessResult r = run_process({"squeue", "-h", "-r", "-t", "all", "-j", job, "-o", "%K|%T"}, 60);
  std::map<int, std::string> states;
  if (r.exit_code != 0) {
    // A job that has left the queue entirely: squeue says "Invalid job id specified".
    if ((r.errors + r.output).find("Invalid job id") != std::string::npos) return states;
    throw SchedulerError("slurm: squeue failed: " + first_line(r.errors + r.output));
  }
  std::istringstream lines(r.output);
  std::string line;
  while (std::getline(lines, line)) {
    const size_t bar = line.find('|');
    if (bar == std::string::npos) continue;
    try {
      states[std::stoi(line.substr(0, bar))] = trimmed(line.substr(bar + 1));
    } catch (const std::exception&) {  // "N/A": not an array task
    }
  }
  // Tasks the controller has forgotten: the accounting database remembers them where there is one (sacct
  // fails with "accounting storage is disabled" where there is not, and is then not asked).
  if (on_path("sacct")) {
    const ProcessResult a = run_process({"sacct", "-n", "-P", "-X", "-j", job, "-o", "JobID,State"}, 60);
    std::istringstream rows(a.exit_code == 0 ? a.output : "");
    while (std::getline(rows, line)) {  // "1234_5|COMPLETED", "1234_5|CANCELLED by 0"
      const size_t under = line.find('_'), bar = line.find('|');
      if (under == std::string::npos || bar == std::string::npos || bar < under) continue;
      try {
        const int task = std::stoi(line.substr(under + 1, bar - under - 1));
        std::string state = trimmed(line.substr(bar + 1));
        state = state.substr(0, state.find(' '));
        states.emplace(task, state);  // squeue's view wins
      } catch (const std::exception&) {  // "1234_[0-3]": pending, not expanded
      }
    }
  }
  return states;
}

bool slurm_active(const std::string& state) {
  for (const char* s : {"PENDING", "RUNNING", "REQUEUED", "REQUEUE_HOLD", "REQUEUE_FED", "SUSPENDED", "COMPLETING",
                        "CONFIGURING", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED", "RESV_DEL_HOLD", "SPECIAL_EXIT"})
    if (state == s) return true;
  return false;
}

}  // namespace weft::farm
