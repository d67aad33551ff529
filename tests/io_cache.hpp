// HDF5 caches: exact round trips, a cache cut short and resumed equals a straight run (positions and
// hash). The weft commands around them are the cli_* topics.
#include "io/builtin_scenes.hpp"
#include "io/cache_file.hpp"
#include "io/scene_file.hpp"
#include "io/trimesh.hpp"
#include "tests/io_cache_fixture.hpp"
#include "tests/scratch_dir_fixture.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::Frames;
using weft::test::same_bits;
using weft::test::ScratchDir;
using weft::test::small_header;

void expect_frames(const CacheReader& r, const Frames& f) {
  ASSERT_EQ(r.frame_count(), int(f.x.size()));
  for (int k = 0; k < r.frame_count(); ++k) {
    EXPECT_EQ(r.frames()[k], f.stats[k].frame);
    EXPECT_TRUE(same_bits(r.positions(k), f.x[k])) << "frame " << k;
    EXPECT_TRUE(same_bits(r.velocities(k), f.v[k])) << "frame " << k;
    const FrameStats &a = r.stats()[k], &b = f.stats[k];
    EXPECT_TRUE(a.frame == b.frame && a.kinetic_energy == b.kinetic_energy && a.max_speed == b.max_speed &&
                a.max_strain == b.max_strain && a.rms_speed == b.rms_speed && a.non_finite == b.non_finite &&
                a.collision.contacts == b.collision.contacts && a.collision.impact_zone_points == b.collision.impact_zone_points && a.seconds == b.seconds &&
                a.schedule.seconds_constraints == b.schedule.seconds_constraints &&
                a.schedule.seconds_collision_passes == b.schedule.seconds_collision_passes &&
                a.schedule.seconds_contacts == b.schedule.seconds_contacts && a.schedule.seconds_smoothing == b.schedule.seconds_smoothing &&
                a.schedule.collision_passes == b.schedule.collision_passes)
        << "stats of frame " << k;
  }
}

TEST(WEFT_TEST_SUITE, cache_round_trip_is_exact) {
  const ScratchDir dir("round_trip");
  const CacheHeader h = small_header(5);
  const Frames f(5, 7, 3, 1);
  const std::string path = dir.file("c.h5");
  {
    CacheWriter w(path, h);
    f.append_to(w, 0, 3);
    EXPECT_EQ(w.frame_count(), 3);
    w.close();
  }
  const CacheReader r(path);
  EXPECT_EQ(r.header().scene, h.scene);
  EXPECT_EQ(r.header().backend, h.backend);
  EXPECT_EQ(r.header().points, 5u);
  EXPECT_EQ(r.header().triangles, h.triangles);
  EXPECT_TRUE(differing_settings(r.header().settings, h.settings).empty());
  expect_frames(r, f);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"c.h5"});
}

TEST(WEFT_TEST_SUITE, cache_takes_its_name_with_the_first_frame_and_failures_leave_nothing) {
  const ScratchDir dir("publish");
  const Frames f(4, 7, 1, 2);
  {
    CacheWriter w(dir.file("c.h5"), small_header(4));
    EXPECT_FALSE(fs::exists(dir.file("c.h5")));
    f.append_to(w, 0, 1);
    EXPECT_TRUE(fs::exists(dir.file("c.h5")));
  }
  { const CacheWriter unfinished(dir.file("never.h5"), small_header(4)); }
  std::ofstream(dir.file("blocker")) << "a file, not a folder";
  EXPECT_THROW(CacheWriter(dir.file("blocker") + "/c.h5", small_header(4)), std::runtime_error);
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"blocker", "c.h5"}));
  const std::string e = [&] {
    try {
      CacheReader r(dir.file("blocker"));
    } catch (const FormatError& x) {
      return std::string(x.what());
    }
    return std::string();
  }();
  EXPECT_NE(e.find(dir.file("blocker") + ": not an HDF5 file"), std::string::npos) << e;
}

// The writer dies without closing (as under SIGKILL): the frames it completed are readable, and a cache
// continued from them holds them and the new ones.
TEST(WEFT_TEST_SUITE, cache_of_a_killed_writer_keeps_its_frames_and_continues) {
  const ScratchDir dir("killed");
  const std::string path = dir.file("c.h5");
  const CacheHeader h = small_header(6);
  const Frames f(6, 7, 5, 3);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    CacheWriter w(path, h);
    f.append_to(w, 0, 3);
    ::_exit(0);  // no destructors, no close
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  {
    const CacheReader r(path);
    Frames first = f;
    for (auto* v : {&first.x, &first.v}) v->resize(3);
    first.stats.resize(3);
    expect_frames(r, first);
  }
  {
    const CacheReader previous(path);
    CacheWriter w(path, h, previous, 3);
    f.append_to(w, 3, 5);
    w.close();
  }
  expect_frames(CacheReader(path), f);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"c.h5"});
}

// What `weft run -o` does, in the library: a cache of a straight run, and one cut after `stop` frames and
// continued from its last frame, hold the same bits, and cache_hash is the run's hash.
TEST(WEFT_TEST_SUITE, cache_resumed_from_a_cut_run_equals_the_straight_run) {
  using Exec = WEFT_TEST_EXECSPACE;
  const ScratchDir dir("resume");
  Scene s = make_builtin_scene("hanging-sheet", {5});
  s.settings.frame_end = 9;
  s.settings.substeps = 4;
  s.settings.iterations = 8;
  const CacheHeader h{s.name, "serial", s.points.size(), s.triangles, s.settings};
  const auto run = [&](const std::string& path, int last_frame, const CacheReader* previous) {
    SimulationOn<Exec> sim(s);
    std::unique_ptr<CacheWriter> w;
    uint64_t hash = 0;
    if (previous) {
      const int k = previous->frame_count();
      sim.set_state(previous->frames().back(), previous->positions(k - 1), previous->velocities(k - 1));
      w = std::make_unique<CacheWriter>(path, h, *previous, k);
    } else {
      hash = hash_combine(0, sim.hash_positions());
      w = std::make_unique<CacheWriter>(path, h);
      w->append(sim.measure(), sim.positions(), sim.velocities());
    }
    while (sim.frame() < last_frame) {
      const FrameStats fs = sim.step_frame();
      w->append(fs, sim.positions(), sim.velocities());
      hash = hash_combine(hash, sim.hash_positions());
    }
    w->close();
    return hash;
  };
  const uint64_t straight_hash = run(dir.file("straight.h5"), 9, nullptr);
  run(dir.file("cut.h5"), 4, nullptr);
  {
    const CacheReader cut(dir.file("cut.h5"));
    ASSERT_EQ(cut.frame_count(), 4);
    run(dir.file("cut.h5"), 9, &cut);
  }
  const CacheReader a(dir.file("straight.h5")), b(dir.file("cut.h5"));
  ASSERT_EQ(a.frame_count(), 9);
  ASSERT_EQ(b.frame_count(), 9);
  for (int k = 0; k < 9; ++k) {
    EXPECT_TRUE(same_bits(a.positions(k), b.positions(k))) << "frame " << k;
    EXPECT_TRUE(same_bits(a.velocities(k), b.velocities(k))) << "frame " << k;
  }
  EXPECT_EQ(cache_hash(a), straight_hash);
  EXPECT_EQ(cache_hash(b), straight_hash);
  uint64_t fixture_hash = 0;
  test::run_frames<Exec>(s, 8, &fixture_hash);
  EXPECT_EQ(cache_hash(a), fixture_hash);
  EXPECT_EQ(positions_hash(a.positions(0)), SimulationOn<Exec>(s).hash_positions());
}

TEST(WEFT_TEST_SUITE, cache_frame_files_are_named_like_houdini_sequences) {
  EXPECT_EQ(frame_file_stem("builtin:hanging-sheet"), "hanging-sheet");
  EXPECT_EQ(frame_file_stem("/shots/sh010/dress v2.h5"), "dress_v2");
  EXPECT_EQ(frame_file_stem(""), "cloth");
  EXPECT_EQ(frame_file("out", "dress", 7, "geo"), (fs::path("out") / "dress.0007.geo").string());
}

}  // namespace
