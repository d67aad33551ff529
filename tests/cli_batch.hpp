// `weft batch` on this machine: plan, submit --scheduler local, status and collect, end to end; and what
// submit refuses before it starts anything. The batch description itself is io_farm; a real Slurm is
// tests/farm_slurm.sh.
#include "io/cache_file.hpp"
#include "tests/cli_fixture.hpp"

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using weft::test::Cli;
using weft::test::ScratchDir;

TEST(WEFT_TEST_SUITE, cli_batch_on_this_machine_runs_every_task_and_collects_a_summary) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_batch_local");
  dir.write("w.json", R"({"name": "w", "tasks": [
    {"name": "a", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-4"},
    {"name": "k", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-4", "wedge": {"bend_stiffness_scale": [0.5, 2]}}
  ]})");
  Cli weft(dir);
  ASSERT_EQ(weft("batch plan " + dir.file("w.json")), 0) << weft.output;
  EXPECT_NE(weft.output.find("batch w: 3 tasks, output " + dir.file("w")), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("k-1   builtin:hanging-sheet --res 4  1-4     bend_stiffness_scale=2"), std::string::npos) << weft.output;
  EXPECT_FALSE(fs::exists(dir.file("w"))) << "plan writes nothing";
  ASSERT_EQ(weft("batch submit " + dir.file("w.json") + " --scheduler local"), 0) << weft.output;
  for (const char* t : {"a", "k-0", "k-1"}) {
    const io::CacheReader c(dir.file(std::string("w/") + t + "/cache.h5"));
    EXPECT_EQ(c.frame_count(), 4) << t;
    EXPECT_EQ(dir.read(std::string("w/") + t + "/exit_code"), "0\n") << t;
  }
  ASSERT_EQ(weft("batch status " + dir.file("w.json")), 0) << weft.output;
  EXPECT_NE(weft.output.find("3 of 3 tasks done"), std::string::npos) << weft.output;
  ASSERT_EQ(weft("batch collect " + dir.file("w.json")), 0) << weft.output;
  ASSERT_EQ(weft("run builtin:hanging-sheet --res 4 --frames 1-4 --set bend_stiffness_scale=2 --hash"), 0) << weft.output;
  const std::string h = weft.hash();
  const std::string md = dir.read("w/summary.md");
  EXPECT_NE(md.find("| k-1 | 2 | done | 4/4 |"), std::string::npos) << md;
  EXPECT_NE(md.find(h), std::string::npos) << "the summary gives the straight run's hash " << h << "\n" << md;
  EXPECT_NE(md.find("![k-1](k-1/sheet.png)"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(dir.file("w/k-1/sheet.png")));
  EXPECT_NE(dir.read("w/summary.html").find("<h2>wedge k</h2>"), std::string::npos);
}

TEST(WEFT_TEST_SUITE, cli_batch_submits_nothing_over_a_cache_of_another_scene_or_without_a_scheduler) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_batch_refusals");
  dir.write("w.json", R"({"name": "w", "tasks": [
    {"name": "a", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-3"},
    {"name": "b", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-3", "set": {"substeps": 2}}]})");
  Cli weft(dir);
  fs::create_directories(dir.file("w/b"));
  ASSERT_EQ(weft("run builtin:hanging-sheet --res 5 --frames 1-2 -o " + dir.file("w/b/cache.h5")), 0) << weft.output;
  EXPECT_EQ(weft("batch submit " + dir.file("w.json") + " --scheduler local"), 2);
  EXPECT_NE(weft.output.find("nothing submitted"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("task b: " + dir.file("w/b/cache.h5") + " belongs to another run (scene builtin:hanging-sheet)"),
            std::string::npos) << weft.output;
  EXPECT_FALSE(fs::exists(dir.file("w/a"))) << "no task ran";
  EXPECT_FALSE(fs::exists(dir.file("w/submission.json")));
  fs::remove_all(dir.file("w"));
  // No Slurm commands on PATH. (A controller that does not answer is refused the same way, after sinfo has
  // waited for it: tests/farm_slurm.sh.)
  EXPECT_EQ(weft("batch submit " + dir.file("w.json") + " --scheduler slurm", "PATH=/nonexistent"), 3);
  EXPECT_NE(weft.output.find("slurm: sbatch is not on PATH"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("nothing submitted"), std::string::npos) << weft.output;
  EXPECT_FALSE(fs::exists(dir.file("w/submission.json")));
}

}  // namespace
