// Pictures from the command line: `weft demo` writes its cache and contact sheet, `weft render` draws a cache
// with the view options it takes. What the pictures hold is io_contact_sheet and io_demo.
#include "io/builtin_scenes.hpp"
#include "io/cache_file.hpp"
#include "tests/cli_fixture.hpp"
#include "tests/io_checks_fixture.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace weft;
using namespace weft::io;
using weft::test::Cli;
using weft::test::png_size;
using weft::test::ScratchDir;

// `weft demo` and `weft render` (the binary, serial backend), when it is built.
TEST(WEFT_TEST_SUITE, cli_demo_writes_a_cache_and_a_contact_sheet) {
  WEFT_NEED_CLI();
  const ScratchDir dir("cli_demo");
  Cli weft(dir);
  const std::string out = dir.file("out");
  ASSERT_EQ(weft("demo --size 700 --frames 1-3 --out " + out), 0) << weft.output;
  const CacheReader cache(out + "/demo.h5");
  EXPECT_EQ(cache.frames(), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(png_size(out + "/contact-sheet.png"), (std::pair<int, int>{3 * 360, 36 + 360}));
  ASSERT_EQ(weft("render " + out + "/demo.h5 -o " + dir.file("any.png") + " --count 2 --cell 128"), 0) << weft.output;
  EXPECT_EQ(png_size(dir.file("any.png")), (std::pair<int, int>{2 * 128, 36 + 128}));
  EXPECT_EQ(weft("render " + out + "/demo.h5 -o " + dir.file("bad.png") + " --frames 1-9"), 2);
  EXPECT_FALSE(fs::exists(dir.file("bad.png")));
}

// `weft render --view/--frame-all/--zoom` (the binary, when it is built).
TEST(WEFT_TEST_SUITE, sheet_cli_takes_view_options) {
  WEFT_NEED_CLI();
  const ScratchDir dir("sheet_cli");
  const Scene s = make_builtin_scene("drape-sphere", {4});
  const std::string cache = dir.file("c.h5");
  {
    CacheWriter w(cache, CacheHeader{s.name, "serial", s.points.size(), s.triangles, s.settings});
    for (int f = s.settings.frame_start; f < s.settings.frame_start + 3; ++f) {
      FrameStats st;
      st.frame = f;
      std::vector<Vec3> x = s.points.position;
      for (Vec3& p : x) p.y -= 0.02 * (f - s.settings.frame_start);
      w.append(st, x, s.points.velocity);
    }
    w.close();
  }
  Cli weft(dir);
  const std::string render = "render " + cache + " --scene builtin:drape-sphere --res 4 --count 2 --cell 96 ";
  ASSERT_EQ(weft(render + "-o " + dir.file("standard.png")), 0) << weft.output;
  ASSERT_EQ(weft(render + "-o " + dir.file("top.png") + " --view top --frame-all --zoom 1.5"), 0) << weft.output;
  EXPECT_EQ(png_size(dir.file("top.png")).first, 2 * 96);
  EXPECT_NE(dir.read("standard.png"), dir.read("top.png"));
  for (const char* bad : {"--view diagonal", "--zoom 0", "--zoom -2"}) {
    EXPECT_NE(weft(render + "-o " + dir.file("bad.png") + " " + bad), 0) << bad;
    EXPECT_FALSE(fs::exists(dir.file("bad.png"))) << bad;
  }
}

}  // namespace
