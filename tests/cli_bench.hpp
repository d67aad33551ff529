// `weft bench` from the command line: settings by name as weft run takes them, one JSON key per figure, and
// the paper's schedules from the table weft run uses (scene/schedules.hpp). Bench times; the tests check only
// what it ran and wrote.
#include "scene/schedules.hpp"
#include "tests/cli_fixture.hpp"

#include <string>

namespace {

using namespace weft;
using weft::test::Cli;
using weft::test::ScratchDir;

// weft bench takes settings by name as weft run does, and its JSON has one key per figure (the scheduled
// passes per substep and the passes per frame, early ones counted, apart).
TEST(WEFT_TEST_SUITE, cli_bench_takes_settings_by_name_and_writes_each_key_once) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_bench");
  Cli weft(dir);
  const std::string json = dir.file("bench.json");
  ASSERT_EQ(weft("bench builtin:drape-sphere --res 4 --frames 1 --warmup 1 --set substeps=3 --set collision_passes=1 "
                 "--json " + json), 0) << weft.output;
  const std::string text = dir.read("bench.json");
  EXPECT_NE(text.find("\"substeps\": 3"), std::string::npos) << text;
  EXPECT_NE(text.find("\"collision_passes\": 1,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"passes_per_frame\": "), std::string::npos) << text;
  EXPECT_EQ(text.find("\"collision_passes\""), text.rfind("\"collision_passes\"")) << text;
  EXPECT_EQ(weft("bench builtin:drape-sphere --res 4 --frames 1 --set substep=3"), 1);  // as weft run
  EXPECT_NE(weft.output.find("unknown setting 'substep'"), std::string::npos) << weft.output;
}

// --schedules paper: a row per schedule of the table, with its settings; --schedules takes nothing else.
TEST(WEFT_TEST_SUITE, cli_bench_schedules_paper_runs_each_named_schedule) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_bench_schedules");
  Cli weft(dir);
  ASSERT_EQ(weft("bench builtin:hanging-sheet --res 2 --frames 1 --warmup 0 --schedules paper --json " +
                 dir.file("bench.json")), 0) << weft.output;
  const std::string text = dir.read("bench.json");
  for (const Schedule& s : kSchedules)
    EXPECT_NE(text.find("{\"schedule\": \"" + std::string(s.name) + "\", \"iterations\": " +
                        std::to_string(s.iterations) + ", \"collision_passes\": " +
                        std::to_string(s.collision_passes) + ", \"substeps\": " + std::to_string(s.substeps) + ","),
              std::string::npos) << s.name << "\n" << text;
  EXPECT_EQ(weft("bench builtin:hanging-sheet --res 2 --schedules all"), 2);
  EXPECT_NE(weft.output.find("--schedules is 'paper' or 'current'"), std::string::npos) << weft.output;
}

}  // namespace
