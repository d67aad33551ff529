// `weft run` from the command line: global options before or after the subcommand, a cache cut short (by a
// stop or SIGINT) and resumed equals a straight run, outputs that cannot be written leave nothing, named
// schedules and settings by name, and each run switch is recorded in the cache and checked on resume.
#include "core/hash.hpp"
#include "io/cache_file.hpp"
#include "io/hdf5_util.hpp"
#include "scene/schedules.hpp"
#include "tests/cli_fixture.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::Cli;
using weft::test::kSheet;
using weft::test::ScratchDir;

TEST(WEFT_TEST_SUITE, cli_global_options_go_before_or_after_the_subcommand) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_global_options");
  // Without OMP_PROC_BIND in the environment, as a user's shell has it: no Kokkos advice is printed either.
  const auto weft = [&](const std::string& args) {
    const std::string log = dir.file("log");
    std::system(("env -u OMP_PROC_BIND " + Cli::binary() + " " + args + " > '" + log + "' 2>&1").c_str());
    return dir.read("log");
  };
  const std::string run = "run builtin:hanging-sheet --res 4 --frames 1-3 --hash";
  const std::string after = weft(run + " --backend serial --threads 1"), before = weft("--backend serial --threads 1 " + run);
  EXPECT_NE(after.find("backend serial"), std::string::npos) << after;
  EXPECT_EQ(after.substr(after.rfind("hash ")), before.substr(before.rfind("hash ")));
  EXPECT_EQ(after.find("OMP_PROC_BIND"), std::string::npos) << after;
  EXPECT_NE(weft("info --backend serial").find("selected backend: serial"), std::string::npos);
  EXPECT_NE(weft(run + " --backend nonsense").find("unknown backend 'nonsense'"), std::string::npos);
}

TEST(WEFT_TEST_SUITE, cli_run_resume_gives_the_straight_runs_cache_and_hash) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_resume");
  Cli weft(dir);
  ASSERT_EQ(weft(kSheet + " --frames 1-9 --hash -o " + dir.file("straight.h5")), 0) << weft.output;
  const std::string straight = weft.hash();
  EXPECT_EQ(straight, hash_hex(cache_hash(CacheReader(dir.file("straight.h5")))));
  ASSERT_EQ(weft(kSheet + " --frames 1-4 -o " + dir.file("resumed.h5")), 0) << weft.output;
  ASSERT_EQ(weft(kSheet + " --frames 1-9 --hash --resume -o " + dir.file("resumed.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("frames 1-4 are done"), std::string::npos) << weft.output;
  EXPECT_EQ(weft.hash(), straight);
  EXPECT_EQ(weft("compare " + dir.file("straight.h5") + " " + dir.file("resumed.h5")), 0) << weft.output;
  EXPECT_EQ(weft.output, "identical (9 frames)\n");
  // Nothing left to do: the cache stays, the hash still covers every frame.
  ASSERT_EQ(weft(kSheet + " --frames 1-9 --hash --resume -o " + dir.file("resumed.h5")), 0) << weft.output;
  EXPECT_EQ(weft.hash(), straight);
  // Another setting would not continue the same run.
  EXPECT_EQ(weft(kSheet + " --frames 1-12 --smoothing 2 --resume -o " + dir.file("resumed.h5")), 2);
  EXPECT_NE(weft.output.find("cannot resume from this cache: it was computed with another smoothing_iterations setting"),
            std::string::npos)
      << weft.output;
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"resumed.h5", "straight.h5"}));
}

TEST(WEFT_TEST_SUITE, cli_sigint_closes_the_cache_after_a_whole_frame_and_resume_finishes) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_sigint");
  Cli weft(dir);
  const std::string cache = dir.file("c.h5"), log = dir.file("interrupted.log");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen(log.c_str(), "w", stdout) || !std::freopen(log.c_str(), "a", stderr)) ::_exit(127);
    const std::string bin = Cli::binary();
    execl(bin.c_str(), bin.c_str(), "--backend", "serial", "run", "builtin:hanging-sheet", "--res", "5", "--substeps",
          "4", "--iterations", "8", "--frames", "1-100000", "-o", cache.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Interrupt once the run has written a couple of frames (a reader may open the cache while it is written).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int written = 0;
  while (written < 3 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (fs::exists(cache)) written = CacheReader(cache).frame_count();
  }
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string message = dir.read("interrupted.log");
  ASSERT_TRUE(WIFEXITED(status)) << message;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << message;
  EXPECT_NE(message.find("stopped by SIGINT after frame"), std::string::npos) << message;
  EXPECT_NE(message.find("--resume"), std::string::npos) << message;
  const int last = [&] { const CacheReader r(cache); return r.frames().back(); }();
  EXPECT_GE(last, 3);
  EXPECT_NE(message.find(cache + " holds frames 1-" + std::to_string(last)), std::string::npos) << message;
  // Closed cleanly: an ordinary (non-SWMR) reader opens it too.
  const hid_t plain = H5Fopen(cache.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(plain, 0);
  if (plain >= 0) H5Fclose(plain);

  const std::string range = " --frames 1-" + std::to_string(last + 3);
  ASSERT_EQ(weft(kSheet + range + " --hash --resume -o " + cache), 0) << weft.output;
  const std::string resumed = weft.hash();
  ASSERT_EQ(weft(kSheet + range + " --hash --quiet"), 0) << weft.output;
  EXPECT_EQ(resumed, weft.hash());
  EXPECT_EQ(CacheReader(cache).frame_count(), last + 3);
}

TEST(WEFT_TEST_SUITE, cli_unwritable_outputs_fail_and_leave_nothing) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_unwritable");
  Cli weft(dir);
  std::ofstream(dir.file("blocker")) << "a file, not a folder";
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("blocker") + "/c.h5"), 0);
  EXPECT_NE(weft.output.find("cannot create " + dir.file("blocker") + "/c.h5"), std::string::npos) << weft.output;
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("c.h5") + " --geo-sequence " + dir.file("blocker") + "/geo"), 0);
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("blocker") + "/c.h5 --geo-sequence " + dir.file("geo")), 0);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"blocker"});
}

// weft run --set NAME=VALUE: kept in the cache's header, checked on resume, listed by --set help.
TEST(WEFT_TEST_SUITE, cli_run_set_is_kept_in_the_cache_and_a_resume_with_other_values_is_refused) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_set");
  Cli weft(dir);
  const std::string run = "run builtin:hanging-sheet --res 4 ";
  ASSERT_EQ(weft(run + "--frames 1-3 --set substeps=3 --set bend_stiffness_scale=2 -o " + dir.file("a.h5")), 0)
      << weft.output;
  EXPECT_EQ(io::CacheReader(dir.file("a.h5")).header().overrides, "substeps=3;bend_stiffness_scale=2");
  EXPECT_EQ(weft(run + "--frames 1-5 --set substeps=4 -o " + dir.file("a.h5") + " --resume"), 2);
  EXPECT_NE(weft.output.find("computed with --set 'substeps=3;bend_stiffness_scale=2', this run with 'substeps=4'"),
            std::string::npos) << weft.output;
  EXPECT_EQ(weft(run + "--frames 1-5 --set substeps=3 --set bend_stiffness_scale=2 --hash -o " + dir.file("a.h5") +
                 " --resume"), 0) << weft.output;
  const std::string resumed = weft.hash();
  ASSERT_EQ(weft(run + "--frames 1-5 --substeps 3 --set bend_stiffness_scale=2 --hash"), 0) << weft.output;
  EXPECT_EQ(resumed, weft.hash());
  EXPECT_EQ(weft(run + "--set substep=3"), 1);
  EXPECT_NE(weft.output.find("unknown setting 'substep'"), std::string::npos) << weft.output;
  EXPECT_EQ(weft(run + "--set help"), 0);
  EXPECT_NE(weft.output.find("stretch_stiffness_scale"), std::string::npos) << weft.output;
}

// weft run --schedule NAME: the row of scene/schedules.hpp, recorded in the cache as plain settings; a name
// the table lacks is refused with the table's names.
TEST(WEFT_TEST_SUITE, cli_run_schedule_sets_the_named_rows_settings) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_schedule");
  Cli weft(dir);
  for (const Schedule& s : kSchedules) {
    SCOPED_TRACE(s.name);
    ASSERT_EQ(weft("run builtin:hanging-sheet --res 2 --frames 1-2 --quiet --schedule " + std::string(s.name) + " -o " +
                   dir.file(std::string(s.name) + ".h5")),
              0) << weft.output;
    ASSERT_EQ(weft("info " + dir.file(std::string(s.name) + ".h5")), 0) << weft.output;
    EXPECT_NE(weft.output.find("substeps " + std::to_string(s.substeps) + ", iterations " +
                               std::to_string(s.iterations) + ", collision passes " +
                               std::to_string(s.collision_passes) + ","),
              std::string::npos) << weft.output;
  }
  EXPECT_EQ(weft("run builtin:hanging-sheet --res 2 --frames 1-2 --schedule paper-0"), 2);
  EXPECT_NE(weft.output.find("unknown schedule 'paper-0' (" + schedule_names() + ")"), std::string::npos)
      << weft.output;
}

// A run switch: `base on` writes a cache whose `weft info` shows `shown`; a resume without the switch is refused
// for another `field` setting (the settings differ), one with it continues; `base bad` is refused naming
// `option`.
struct Switch {
  std::string base, on, shown, field, bad, option;
};

void expect_recorded_and_resumed(Cli& weft, const ScratchDir& dir, const Switch& s) {
  const std::string run = s.base + " " + s.on + " -o " + dir.file("c.h5");
  ASSERT_EQ(weft(run + " --frames 1-4"), 0) << weft.output;
  ASSERT_EQ(weft("info " + dir.file("c.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find(s.shown), std::string::npos) << weft.output;
  EXPECT_EQ(weft(s.base + " --frames 1-6 --resume -o " + dir.file("c.h5")), 2);
  EXPECT_NE(weft.output.find("another " + s.field + " setting"), std::string::npos) << weft.output;
  ASSERT_EQ(weft(run + " --frames 1-6 --resume"), 0) << weft.output;
  EXPECT_NE(weft(s.base + " --frames 1-2 " + s.bad), 0);
  EXPECT_NE(weft.output.find(s.option), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_chebyshev_setting_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_chebyshev");
  Cli weft(dir);
  const std::string run = kSheet + " --set chebyshev_rho=0.9 -o " + dir.file("c.h5");
  ASSERT_EQ(weft(run + " --frames 1-4"), 0) << weft.output;
  ASSERT_EQ(weft("info " + dir.file("c.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("Chebyshev rate 0.9 after 4 iterations"), std::string::npos) << weft.output;
  // A resume must repeat the run's --set: the refusal names it.
  EXPECT_EQ(weft(kSheet + " --frames 1-6 --resume -o " + dir.file("c.h5")), 2);
  EXPECT_NE(weft.output.find("chebyshev_rho=0.9"), std::string::npos) << weft.output;
  // Off is a setting like any other: recorded and shown.
  ASSERT_EQ(weft(kSheet + " --frames 1-2 --set chebyshev_rho=0 -o " + dir.file("off.h5")), 0) << weft.output;
  ASSERT_EQ(weft("info " + dir.file("off.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("Chebyshev off"), std::string::npos) << weft.output;
  ASSERT_EQ(weft(run + " --frames 1-6 --resume"), 0) << weft.output;
  EXPECT_NE(weft(kSheet + " --frames 1-2 --set chebyshev_rho=1.5"), 0);
  EXPECT_NE(weft.output.find("chebyshev_rho"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_self_collision_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_self_collision");
  Cli weft(dir);
  // The hanging sheet has no self collision of its own; --self-collision on adds the collision stage.
  expect_recorded_and_resumed(weft, dir, {kSheet, "--self-collision on", "self collision on", "self_collision",
                                          "--self-collision sometimes", "--self-collision"});
  ASSERT_EQ(weft("check-intersections " + dir.file("c.h5") + " --all-frames"), 0) << weft.output;
  EXPECT_NE(weft.output.find("\nintersections 0\n"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_contact_model_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_contact_model");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet", "--contact-model ccd",
                                          "contact model ccd", "contact_model", "--contact-model ipc",
                                          "--contact-model"});
  // The default reports its passes, full queries and still passes per frame. The stack falls as one body
  // (nothing moves beside the common translation), so every pass after the frame's query is still; with
  // still_tolerance 0 each of them measures its pairs.
  ASSERT_EQ(weft("run builtin:layer-stack --res 4 --frames 1-2"), 0) << weft.output;
  EXPECT_NE(weft.output.find("passes 20 (0 early, 1 full queries, 19 still)"), std::string::npos) << weft.output;
  ASSERT_EQ(weft("run builtin:layer-stack --res 4 --frames 1-2 --set still_tolerance=0"), 0) << weft.output;
  EXPECT_NE(weft.output.find("passes 20 (0 early, 1 full queries, 0 still)"), std::string::npos) << weft.output;
  // The default's cache tells what it ran: Jacobi contacts, no fail-safe or CCD span of the ccd model.
  ASSERT_EQ(weft("run builtin:layer-stack --res 4 --frames 1-2 --quiet -o " + dir.file("p.h5")), 0) << weft.output;
  ASSERT_EQ(weft("info " + dir.file("p.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("contacts jacobi (every contact a row)"), std::string::npos) << weft.output;
  EXPECT_EQ(weft.output.find("fail-safe"), std::string::npos) << weft.output;
  EXPECT_EQ(weft.output.find("CCD span"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_pair_refresh_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_pair_refresh");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet", "--pair-refresh off",
                                          "pair refresh off", "pair_refresh", "--pair-refresh sometimes",
                                          "--pair-refresh"});
}

TEST(WEFT_TEST_SUITE, cli_contact_solver_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_contact_solver");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet --contact-model ccd",
                                          "--contact-solver jacobi", "contact solver jacobi", "contact_solver",
                                          "--contact-solver sor", "--contact-solver"});
}

TEST(WEFT_TEST_SUITE, cli_ccd_span_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_ccd_span");
  Cli weft(dir);
  const std::string span = CollisionSettings{}.ccd_span == CcdSpan::Pass ? "substep" : "pass";  // not the default
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet --contact-model ccd", "--ccd-span " + span,
                                          "CCD span " + span, "ccd_span", "--ccd-span frame", "--ccd-span"});
}

TEST(WEFT_TEST_SUITE, cli_tethers_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_tethers");
  Cli weft(dir);
  const std::string sheet = "run builtin:hanging-sheet --res 5 --substeps 1 --iterations 5";
  expect_recorded_and_resumed(weft, dir, {sheet + " --quiet", "--tethers 1.05", "tethers 1.05", "tether_stretch",
                                          "--tethers 0.5", "--tethers"});
  ASSERT_EQ(weft(sheet + " --frames 1-2 --tethers 1"), 0) << weft.output;
  EXPECT_NE(weft.output.find(" 34 tethers,"), std::string::npos) << weft.output;  // 36 points, 2 pinned
}

}  // namespace
