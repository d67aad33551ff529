// HDF5 caches: exact round trips, a cache cut short and resumed equals a straight run (positions and
// hash), and the weft commands around them (run -o / --geo-sequence / --resume, SIGINT, compare, export, info).
#include "io/builtin_scenes.hpp"
#include "io/cache_file.hpp"
#include "io/hdf5_util.hpp"
#include "io/houdini_geo.hpp"
#include "io/obj.hpp"
#include "io/scene_file.hpp"
#include "tests/solver_scene_fixture.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;

struct CacheDir {
  fs::path path;
  explicit CacheDir(const std::string& name)
      : path(fs::temp_directory_path() / ("weft_io_cache_" + std::to_string(::getpid()) + "_" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~CacheDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::set<std::string> entries(const std::string& sub = "") const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(path / sub)) names.insert(e.path().filename().string());
    return names;
  }
};

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

std::vector<Vec3> random_vectors(test::TestRng& rng, size_t n) {
  std::vector<Vec3> v(n);
  for (Vec3& p : v) p = {rng.uniform(-1, 1), rng.uniform(-1e-300, 1e-300), rng.uniform(-1e300, 1e300)};
  return v;
}

CacheHeader small_header(size_t points) {
  CacheHeader h;
  h.scene = "builtin:test";
  h.backend = "serial";
  h.points = points;
  for (int i = 0; i + 2 < int(points); ++i) h.triangles.push_back({i, i + 1, i + 2});
  h.settings.frame_start = 7;
  h.settings.frame_end = 20;
  h.settings.fps = 30;
  h.settings.wind = {1.0 / 3, 0, 0};
  return h;
}

FrameStats stats_of(int frame) {
  FrameStats s;
  s.frame = frame;
  s.kinetic_energy = 1.0 / frame;
  s.max_speed = 2.0 / frame;
  s.max_strain = 3.0 / frame;
  s.rms_speed = 4.0 / frame;
  s.non_finite = frame + 1;
  s.contacts = frame + 2;
  s.impact_zone_points = frame + 3;
  s.seconds = 0.5 / frame;
  s.seconds_constraints = 0.25 / frame;
  s.seconds_collision_passes = 0.125 / frame;
  s.seconds_contacts = 0.0625 / frame;
  s.seconds_smoothing = 0.03125 / frame;
  s.collision_passes = frame + 4;
  return s;
}

// Frames appended to a cache: positions, velocities, statistics.
struct Frames {
  std::vector<std::vector<Vec3>> x, v;
  std::vector<FrameStats> stats;
  Frames(size_t points, int first, int count, uint64_t seed) {
    test::TestRng rng(seed);
    for (int k = 0; k < count; ++k) {
      x.push_back(random_vectors(rng, points));
      v.push_back(random_vectors(rng, points));
      stats.push_back(stats_of(first + k));
    }
  }
  void append_to(CacheWriter& w, int from, int to) const {
    for (int k = from; k < to; ++k) w.append(stats[k], x[k], v[k]);
  }
};

void expect_frames(const CacheReader& r, const Frames& f) {
  ASSERT_EQ(r.frame_count(), int(f.x.size()));
  for (int k = 0; k < r.frame_count(); ++k) {
    EXPECT_EQ(r.frames()[k], f.stats[k].frame);
    EXPECT_TRUE(same_bits(r.positions(k), f.x[k])) << "frame " << k;
    EXPECT_TRUE(same_bits(r.velocities(k), f.v[k])) << "frame " << k;
    const FrameStats &a = r.stats()[k], &b = f.stats[k];
    EXPECT_TRUE(a.frame == b.frame && a.kinetic_energy == b.kinetic_energy && a.max_speed == b.max_speed &&
                a.max_strain == b.max_strain && a.rms_speed == b.rms_speed && a.non_finite == b.non_finite &&
                a.contacts == b.contacts && a.impact_zone_points == b.impact_zone_points && a.seconds == b.seconds &&
                a.seconds_constraints == b.seconds_constraints &&
                a.seconds_collision_passes == b.seconds_collision_passes &&
                a.seconds_contacts == b.seconds_contacts && a.seconds_smoothing == b.seconds_smoothing &&
                a.collision_passes == b.collision_passes)
        << "stats of frame " << k;
  }
}

TEST(WEFT_TEST_SUITE, cache_round_trip_is_exact) {
  const CacheDir dir("round_trip");
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
  const CacheDir dir("publish");
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
  const CacheDir dir("killed");
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
  const CacheDir dir("resume");
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

// The weft binary.
class Cli {
 public:
  explicit Cli(const CacheDir& dir) : dir_(dir) {}
  static bool available() { return fs::exists(binary()); }
  static std::string binary() { return std::string(WEFT_BIN_DIR) + "/weft"; }
  // Runs `weft <args>` (serial backend), keeps its output, returns its exit status.
  int operator()(const std::string& args) {
    const std::string log = dir_.file("weft.log");
    const int status = std::system((binary() + " --backend serial " + args + " > '" + log + "' 2>&1").c_str());
    std::ifstream in(log);
    output = std::string(std::istreambuf_iterator<char>(in), {});
    fs::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string hash() const {  // the value of the run's "hash" line
    const size_t at = output.rfind("hash ");
    return at == std::string::npos ? "" : output.substr(at + 5, 16);
  }
  std::string output;

 private:
  const CacheDir& dir_;
};

#define WEFT_NEED_CLI() \
  if (!Cli::available()) GTEST_SKIP() << Cli::binary() << " is not built"

const std::string kSheet = "run builtin:hanging-sheet --res 5 --substeps 4 --iterations 8";

TEST(WEFT_TEST_SUITE, cli_global_options_go_before_or_after_the_subcommand) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_global_options");
  // Without OMP_PROC_BIND in the environment, as a user's shell has it: no Kokkos advice is printed either.
  const auto weft = [&](const std::string& args) {
    const std::string log = dir.file("log");
    std::system(("env -u OMP_PROC_BIND " + Cli::binary() + " " + args + " > '" + log + "' 2>&1").c_str());
    std::ifstream in(log);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string run = "run builtin:hanging-sheet --res 4 --frames 1-3 --hash";
  const std::string after = weft(run + " --backend serial --threads 1"), before = weft("--backend serial --threads 1 " + run);
  EXPECT_NE(after.find("backend serial"), std::string::npos) << after;
  EXPECT_EQ(after.substr(after.rfind("hash ")), before.substr(before.rfind("hash ")));
  EXPECT_EQ(after.find("OMP_PROC_BIND"), std::string::npos) << after;
  EXPECT_NE(weft("info --backend serial").find("selected backend: serial"), std::string::npos);
  EXPECT_NE(weft(run + " --backend nonsense").find("unknown backend 'nonsense'"), std::string::npos);
}

// weft bench takes settings by name as weft run does, and its JSON has one key per figure (the scheduled
// passes per substep and the passes per frame, early ones counted, apart).
TEST(WEFT_TEST_SUITE, cli_bench_takes_settings_by_name_and_writes_each_key_once) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_bench");
  Cli weft(dir);
  const std::string json = dir.file("bench.json");
  ASSERT_EQ(weft("bench builtin:drape-sphere --res 4 --frames 1 --warmup 1 --set substeps=3 --set collision_passes=1 "
                 "--json " + json), 0) << weft.output;
  std::ifstream in(json);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("\"substeps\": 3"), std::string::npos) << text;
  EXPECT_NE(text.find("\"collision_passes\": 1,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"passes_per_frame\": "), std::string::npos) << text;
  EXPECT_EQ(text.find("\"collision_passes\""), text.rfind("\"collision_passes\"")) << text;
  EXPECT_EQ(weft("bench builtin:drape-sphere --res 4 --frames 1 --set substep=3"), 1);  // as weft run
  EXPECT_NE(weft.output.find("unknown setting 'substep'"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_run_resume_gives_the_straight_runs_cache_and_hash) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_resume");
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
  const CacheDir dir("cli_sigint");
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
  std::ifstream in(log);
  const std::string message(std::istreambuf_iterator<char>(in), {});
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

// Two caches of 3 frames; the second differs at frame 8 (stored frame 1), point 3, position y, by 3 ULPs.
void write_pair(const CacheDir& dir) {
  const Frames f(5, 7, 3, 4);
  Frames g = f;
  for (int i = 0; i < 3; ++i) g.x[1][3].y = std::nextafter(g.x[1][3].y, 2.0);
  for (const auto& [name, frames] : {std::pair<const char*, const Frames*>{"a.h5", &f}, {"b.h5", &g}}) {
    CacheWriter w(dir.file(name), small_header(5));
    frames->append_to(w, 0, 3);
    w.close();
  }
}

TEST(WEFT_TEST_SUITE, cli_compare_reports_the_first_difference) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_compare");
  write_pair(dir);
  Cli weft(dir);
  const std::string a = dir.file("a.h5"), b = dir.file("b.h5");
  EXPECT_EQ(weft("compare " + a + " " + a), 0);
  EXPECT_EQ(weft.output, "identical (3 frames)\n");
  EXPECT_EQ(weft("compare " + a + " " + b), 1);
  EXPECT_NE(weft.output.find("different: frame 8 point 3 position.y:"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("3 ULPs apart"), std::string::npos) << weft.output;
  EXPECT_EQ(weft("compare --ulp 2 " + a + " " + b), 1);
  EXPECT_EQ(weft("compare --ulp 3 " + a + " " + b), 0);
  EXPECT_EQ(weft.output, "within 3 ULPs (3 frames; largest difference 3 ULPs)\n");
  EXPECT_EQ(weft("compare " + a + " " + dir.file("absent.h5")), 2);
  EXPECT_NE(weft.output.find(dir.file("absent.h5") + ": no such file"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_geo_sequence_and_export_write_one_file_per_frame) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_files");
  Cli weft(dir);
  const std::string cache = dir.file("c.h5");
  ASSERT_EQ(weft(kSheet + " --frames 1-4 -o " + cache + " --geo-sequence " + dir.file("geo")), 0) << weft.output;
  EXPECT_EQ(dir.entries("geo"), (std::set<std::string>{"hanging-sheet.0001.geo", "hanging-sheet.0002.geo",
                                                       "hanging-sheet.0003.geo", "hanging-sheet.0004.geo"}));
  const CacheReader r(cache);
  const Geometry g = read_geo(dir.file("geo/hanging-sheet.0004.geo"));
  ASSERT_EQ(g.points.size(), r.header().points);
  ASSERT_EQ(g.primitives.size(), r.header().triangles.size());
  ASSERT_EQ(g.point_attributes.count("v"), 1u);
  const std::vector<Vec3> x = r.positions(3), v = r.velocities(3);
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(g.points[i].y, double(float(x[i].y))) << "point " << i;
    EXPECT_EQ(g.point_attributes.at("v").number(i, 1), double(float(v[i].y))) << "point " << i;
  }

  ASSERT_EQ(weft("export " + cache + " --format obj " + dir.file("obj") + " --frames 2-3"), 0) << weft.output;
  EXPECT_EQ(dir.entries("obj"), (std::set<std::string>{"hanging-sheet.0002.obj", "hanging-sheet.0003.obj"}));
  const TriMesh m = read_obj(dir.file("obj/hanging-sheet.0003.obj"));
  EXPECT_TRUE(same_bits(m.positions, r.positions(2)));
  EXPECT_EQ(m.triangles, r.header().triangles);
  EXPECT_EQ(weft("export " + cache + " " + dir.file("geo2")), 0) << weft.output;
  EXPECT_EQ(dir.entries("geo2"), dir.entries("geo"));
  EXPECT_EQ(weft("export " + cache + " " + dir.file("geo3") + " --frames 3-5"), 2);
}

TEST(WEFT_TEST_SUITE, cli_unwritable_outputs_fail_and_leave_nothing) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_unwritable");
  Cli weft(dir);
  std::ofstream(dir.file("blocker")) << "a file, not a folder";
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("blocker") + "/c.h5"), 0);
  EXPECT_NE(weft.output.find("cannot create " + dir.file("blocker") + "/c.h5"), std::string::npos) << weft.output;
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("c.h5") + " --geo-sequence " + dir.file("blocker") + "/geo"), 0);
  EXPECT_NE(weft(kSheet + " --frames 1-3 -o " + dir.file("blocker") + "/c.h5 --geo-sequence " + dir.file("geo")), 0);
  EXPECT_EQ(dir.entries(), std::set<std::string>{"blocker"});
}

TEST(WEFT_TEST_SUITE, cli_check_intersections_counts_a_static_obj_mesh) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_check_obj");
  Cli weft(dir);
  // Triangle 1 pierces triangle 2; triangle 3 shares a vertex with 1 (adjacent, not counted) and is far from 2.
  std::ofstream(dir.file("m.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "v 0.2 0.2 -0.5\nv 0.3 0.2 0.5\nv 0.2 0.3 0.5\n"
                                      "v -1 0 0\nv 0 -1 0\n"
                                      "f 1 2 3\nf 4 5 6\nf 1 7 8\n";
  ASSERT_EQ(weft("check-intersections " + dir.file("m.obj")), 0) << weft.output;
  EXPECT_EQ(weft.output, "intersections 1\n");
  std::ofstream(dir.file("bad.obj")) << "v 0 0 0\nf 1 2 3\n";
  EXPECT_NE(weft("check-intersections " + dir.file("bad.obj")), 0);
  EXPECT_NE(weft.output.find("bad.obj"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_info_describes_scene_and_cache_files) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_info");
  Cli weft(dir);
  write_scene(make_builtin_scene("hanging-sheet", {5}), dir.file("s.h5"));
  ASSERT_EQ(weft("info " + dir.file("s.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("weft scene, format version 1"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("points 36, triangles 50"), std::string::npos) << weft.output;
  ASSERT_EQ(weft(kSheet + " --frames 1-3 --quiet --hash -o " + dir.file("c.h5")), 0) << weft.output;
  const std::string hash = weft.hash();
  ASSERT_EQ(weft("info " + dir.file("c.h5")), 0) << weft.output;
  EXPECT_NE(weft.output.find("weft cache, format version 1"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("frames 1-3 (3 stored, complete)"), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find("hash " + hash), std::string::npos) << weft.output;
  std::ofstream(dir.file("text.h5")) << "text";
  EXPECT_EQ(weft("info " + dir.file("text.h5")), 2);
  EXPECT_NE(weft.output.find("not an HDF5 file"), std::string::npos) << weft.output;
}

// A run switch: `base on` writes a cache whose `weft info` shows `shown`; a resume without the switch is refused
// for another `field` setting (the settings differ), one with it continues; `base bad` is refused naming
// `option`.
struct Switch {
  std::string base, on, shown, field, bad, option;
};

void expect_recorded_and_resumed(Cli& weft, const CacheDir& dir, const Switch& s) {
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

TEST(WEFT_TEST_SUITE, cli_self_collision_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_self_collision");
  Cli weft(dir);
  // The hanging sheet has no self collision of its own; --self-collision on adds the collision stage.
  expect_recorded_and_resumed(weft, dir, {kSheet, "--self-collision on", "self collision on", "self_collision",
                                          "--self-collision sometimes", "--self-collision"});
  ASSERT_EQ(weft("check-intersections " + dir.file("c.h5") + " --all-frames"), 0) << weft.output;
  EXPECT_NE(weft.output.find("\nintersections 0\n"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_contact_model_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_contact_model");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet", "--contact-model ccd",
                                          "contact model ccd", "contact_model", "--contact-model ipc",
                                          "--contact-model"});
  // The default reports its passes and full queries per frame.
  ASSERT_EQ(weft("run builtin:layer-stack --res 4 --frames 1-2"), 0) << weft.output;
  EXPECT_NE(weft.output.find("passes 20 ("), std::string::npos) << weft.output;
  EXPECT_NE(weft.output.find(" full queries)"), std::string::npos) << weft.output;
}

TEST(WEFT_TEST_SUITE, cli_pair_refresh_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_pair_refresh");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet", "--pair-refresh off",
                                          "pair refresh off", "pair_refresh", "--pair-refresh sometimes",
                                          "--pair-refresh"});
}

TEST(WEFT_TEST_SUITE, cli_contact_solver_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_contact_solver");
  Cli weft(dir);
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet --contact-model ccd",
                                          "--contact-solver jacobi", "contact solver jacobi", "jacobi_contacts",
                                          "--contact-solver sor", "--contact-solver"});
}

TEST(WEFT_TEST_SUITE, cli_ccd_span_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_ccd_span");
  Cli weft(dir);
  const std::string span = SolverSettings{}.ccd_per_pass ? "substep" : "pass";  // not the default
  expect_recorded_and_resumed(weft, dir, {"run builtin:layer-stack --res 4 --quiet --contact-model ccd", "--ccd-span " + span,
                                          "CCD span " + span, "ccd_per_pass", "--ccd-span frame", "--ccd-span"});
}

TEST(WEFT_TEST_SUITE, cli_tethers_switch_is_recorded_and_resumed) {
  WEFT_NEED_CLI();
  const CacheDir dir("cli_tethers");
  Cli weft(dir);
  const std::string sheet = "run builtin:hanging-sheet --res 5 --substeps 1 --iterations 5";
  expect_recorded_and_resumed(weft, dir, {sheet + " --quiet", "--tethers 1.05", "tethers 1.05", "tether_stretch",
                                          "--tethers 0.5", "--tethers"});
  ASSERT_EQ(weft(sheet + " --frames 1-2 --tethers 1"), 0) << weft.output;
  EXPECT_NE(weft.output.find(" 34 tethers,"), std::string::npos) << weft.output;  // 36 points, 2 pinned
}

}  // namespace
