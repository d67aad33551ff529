// Batches (farm/): descriptions expanded into tasks, settings by name (weft run --set), the Slurm job script.
// `weft batch` on this machine end to end is cli_batch; the run on a real Slurm is tests/farm_slurm.sh.
#include "core/error.hpp"
#include "farm/batch.hpp"
#include "farm/scheduler.hpp"
#include "io/builtin_scenes.hpp"
#include "io/scene_overrides.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <string>

namespace {

using namespace weft;
using weft::test::ScratchDir;

std::string error_of(const std::string& path) {
  try {
    farm::read_batch(path, "/usr/bin/weft");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kWedge = R"({
  "name": "w", "output": "out", "threads": 1,
  "tasks": [
    {"name": "shot", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-3"},
    {"name": "fr", "scene": "builtin:hanging-sheet", "res": 4, "frames": "1-3", "set": {"substeps": 3},
     "wedge": {"static_friction": [0.1, 0.5, 0.9], "self_collision": [true, false]}},
    {"name": "st", "scene": "builtin:hanging-sheet", "res": 4,
     "wedge": {"stretch_stiffness_scale": [0.5, 2], "thickness": [0.001, 0.002]}, "combine": "list"}
  ],
  "slurm": {"partition": "cfx", "gpus_per_task": 1, "time": "01:00:00", "max_parallel": 2,
            "sbatch_args": ["--account=shots"]}
})";

TEST(WEFT_TEST_SUITE, batch_wedges_expand_to_the_product_or_the_list_of_their_values) {
  const ScratchDir dir("batch_expand");
  dir.write("w.json", kWedge);
  const farm::Batch b = farm::read_batch(dir.file("w.json"), "/opt/weft/bin/weft");
  EXPECT_EQ(b.name, "w");
  EXPECT_EQ(b.output, dir.file("out"));
  ASSERT_EQ(b.tasks.size(), 1u + 6u + 2u);
  EXPECT_EQ(b.tasks[0].name, "shot");
  EXPECT_EQ(b.tasks[0].dir, dir.file("out/shot"));
  EXPECT_TRUE(b.tasks[0].wedge.empty());
  // Product: the first setting varies slowest; the task's own settings come first.
  const char* expected[6][2] = {{"0.1", "on"}, {"0.1", "off"}, {"0.5", "on"}, {"0.5", "off"}, {"0.9", "on"}, {"0.9", "off"}};
  for (int k = 0; k < 6; ++k) {
    const farm::Task& t = b.tasks[size_t(1 + k)];
    EXPECT_EQ(t.name, "fr-" + std::to_string(k));
    EXPECT_EQ(t.wedge_name, "fr");
    ASSERT_EQ(t.set.size(), 3u);
    EXPECT_EQ(t.set[0].name + "=" + t.set[0].value, "substeps=3");
    EXPECT_EQ(t.set[1].name + "=" + t.set[1].value, std::string("static_friction=") + expected[k][0]);
    EXPECT_EQ(t.set[2].name + "=" + t.set[2].value, std::string("self_collision=") + expected[k][1]);
    EXPECT_EQ(t.wedge.size(), 2u);
  }
  // List: the k-th values together.
  EXPECT_EQ(b.tasks[7].name, "st-0");
  EXPECT_EQ(io::overrides_text(b.tasks[7].set), "stretch_stiffness_scale=0.5;thickness=0.001");
  EXPECT_EQ(io::overrides_text(b.tasks[8].set), "stretch_stiffness_scale=2;thickness=0.002");
  EXPECT_EQ(farm::shell_line(farm::task_command(b, b.tasks[1])),
            "/opt/weft/bin/weft --threads 1 run builtin:hanging-sheet --res 4 --frames 1-3 --set substeps=3 --set "
            "static_friction=0.1 --set self_collision=on -o " + dir.file("out/fr-0/cache.h5") + " --resume --hash");
}

TEST(WEFT_TEST_SUITE, batch_errors_name_the_file_the_task_and_the_setting) {
  const ScratchDir dir("batch_errors");
  const auto check = [&](const std::string& text, const std::string& wanted) {
    dir.write("b.json", text);
    const std::string e = error_of(dir.file("b.json"));
    EXPECT_NE(e.find(dir.file("b.json")), std::string::npos) << e;
    EXPECT_NE(e.find(wanted), std::string::npos) << "wanted '" << wanted << "' in: " << e;
  };
  const std::string head = R"({"tasks": [{"name": "a", "scene": "builtin:hanging-sheet", )";
  check(head + R"("wedge": {"frction": [0.1]}}]})", "tasks[0] (a).wedge.frction[0]: unknown setting 'frction'");
  check(head + R"("wedge": {"static_friction": [0.1, "high"]}}]})",
        "tasks[0] (a).wedge.static_friction[1]: static_friction: expected a number, got 'high'");
  check(head + R"("set": {"substeps": 0}}]})", "tasks[0] (a).set.substeps: substeps: expected an integer >= 1");
  check(head + R"("wedge": {"substeps": [1, 2], "iterations": [3]}, "combine": "list"}]})",
        "wedge.iterations: has 1 values, 'substeps' 2");
  check(head + R"("frames": "9-2"}]})", "tasks[0] (a).frames: expected \"A-B\"");
  check(R"({"tasks": [{"name": "a", "scene": "missing.json"}]})", "missing.json does not exist");
  check(R"({"tasks": [{"name": "a/b", "scene": "builtin:twist"}]})", "a folder name");
  check(R"({"tasks": [{"name": "a", "scene": "builtin:twist"}, {"name": "a", "scene": "builtin:twist"}]})",
        "two tasks are named 'a'");
  check(R"({"tasks": [{"name": "a", "scene": "builtin:twist", "speed": 1}]})", "tasks[0] (a).speed: unknown key");
  check(R"({"tasks": []})", "tasks: expected a non-empty array");
  check(R"({"tasks": [)", "parse error");
}

TEST(WEFT_TEST_SUITE, settings_by_name_change_the_solver_settings_and_the_cloth) {
  Scene s = io::make_builtin_scene("hanging-sheet", io::BuiltinOptions{4});
  const real compliance = s.constraints.distance.at(0).m.compliance;
  const real bend = s.constraints.bend.at(0).m.compliance;
  io::apply_overrides(s, {{"substeps", "7"}, {"gravity", "0,-1.5,0"}, {"contact_model", "ccd"},
                          {"pair_refresh", "off"}, {"merge_contacts", "off"}, {"nearest_margins", "on"}, {"predicted_reference", "on"}, {"layer_shock", "50"}, {"still_tolerance", "0.25"}, {"thickness", "0.004"}, {"stretch_stiffness_scale", "4"},
                          {"bend_stiffness_scale", "0.5"}});
  EXPECT_EQ(s.settings.substeps, 7);
  EXPECT_EQ(s.settings.gravity.y, -1.5);
  EXPECT_EQ(s.settings.collision.contact_model, ContactModel::Ccd);
  EXPECT_FALSE(s.settings.collision.pair_refresh);
  EXPECT_FALSE(s.settings.collision.merge_contacts);
  EXPECT_TRUE(s.settings.collision.nearest_margins);
  EXPECT_TRUE(s.settings.collision.predicted_reference);
  EXPECT_EQ(s.settings.collision.layer_shock, 50);
  EXPECT_EQ(s.settings.collision.still_tolerance, 0.25);
  for (real t : s.points.thickness) EXPECT_EQ(t, 0.004);
  EXPECT_EQ(s.constraints.distance.at(0).m.compliance, compliance / 4);
  EXPECT_EQ(s.constraints.bend.at(0).m.compliance, bend / 0.5);
  for (const char* bad : {"substeps=-1", "gravity=1,2", "contact_model=soft", "tethers=0.5", "thickness=-1",
                          "pair_refresh=maybe", "fps=0", "layer_shock=0.5", "still_tolerance=-1"})
    EXPECT_THROW(io::check_override(io::parse_override(bad)), InputError) << bad;
  EXPECT_THROW(io::parse_override("substeps"), InputError);
  EXPECT_THROW(io::parse_override("=3"), InputError);
}

TEST(WEFT_TEST_SUITE, slurm_script_runs_each_task_as_one_array_element_that_resumes) {
  const ScratchDir dir("batch_script");
  dir.write("w.json", kWedge);
  const farm::Batch b = farm::read_batch(dir.file("w.json"), "/opt/weft/bin/weft");
  const std::string s = farm::slurm_script(b);
  for (const std::string& line : {"#SBATCH --array=0-8%2", "#SBATCH --requeue", "#SBATCH --partition=cfx",
                                  "#SBATCH --gres=gpu:1", "#SBATCH --time=01:00:00", "#SBATCH --account=shots",
                                  "#SBATCH --open-mode=append"})
    EXPECT_NE(s.find(line + std::string("\n")), std::string::npos) << line << "\n" << s;
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const std::string c = farm::shell_line(farm::task_command(b, b.tasks[k]));
    EXPECT_NE(s.find("  " + std::to_string(k) + ") dir=" + b.tasks[k].dir + "\n     cmd=(" + c + ") ;;"),
              std::string::npos) << k << "\n" << s;
    EXPECT_NE(c.find(" --resume"), std::string::npos);
  }
  EXPECT_NE(s.find("echo \"$rc\" > \"$dir/exit_code\""), std::string::npos);
  EXPECT_EQ(farm::shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(farm::shell_quote("a b"), "'a b'");
  EXPECT_EQ(farm::shell_quote("--set=x,y"), "--set=x,y");
}

}  // namespace
