// Contact sheets (io/contact_sheet.cpp), read back pixel by pixel from the PNG: a depth test (a collider behind
// cloth stays hidden even where sorting triangles would draw it on top; one in front covers the cloth), no
// cracks between neighbouring triangles, both sides of the cloth lit and told apart, the cloth framed (not a
// ground plane around it) unless frame_all, the same bytes twice. `weft render`'s view options are cli_render.
#include "io/contact_sheet.hpp"
#include "tests/scratch_dir_fixture.hpp"

#include <cairo.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace weft;
using namespace weft::io;
using test::ScratchDir;

constexpr int kTitle = 36, kLabel = 28;  // the title band above the cells, each cell's label band, in pixels

struct Rgb8 { int r, g, b; };

// A PNG's pixels, read with Cairo.
struct Image {
  int width = 0, height = 0;
  std::vector<uint32_t> px;
  explicit Image(const std::string& path) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
      cairo_surface_flush(s);
      width = cairo_image_surface_get_width(s), height = cairo_image_surface_get_height(s);
      const int stride = cairo_image_surface_get_stride(s);
      const unsigned char* data = cairo_image_surface_get_data(s);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) px.push_back(reinterpret_cast<const uint32_t*>(data + size_t(y) * stride)[x]);
    }
    cairo_surface_destroy(s);
  }
  Rgb8 at(int x, int y) const {
    const uint32_t v = px[size_t(y) * width + x];
    return {int(v >> 16 & 0xff), int(v >> 8 & 0xff), int(v & 0xff)};
  }
};

// The colliders' grey (lit or not), and the first layer's red (lit or not, either side).
bool grey(Rgb8 c) { return std::abs(c.r - c.g) < 12 && std::abs(c.g - c.b) < 12 && c.r < 200 && c.r > 20; }
bool red(Rgb8 c) { return c.r > 60 && c.r > c.g + 40 && c.r > c.b + 40; }

struct Box {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1, count = 0;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

// The bounding box of the pixels of cell `i` (one row of cells of `cell` pixels) below its label band and
// inside its border for which `is` holds.
template <class Pred>
Box find(const Image& im, int i, int cell, Pred is) {
  Box b;
  for (int y = kTitle + kLabel; y < kTitle + cell - 1; ++y)
    for (int x = i * cell + 1; x < (i + 1) * cell - 1; ++x)
      if (is(im.at(x, y))) {
        b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x), b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
        ++b.count;
      }
  return b;
}

// A square of cloth (side `side`, centre `c`) in the plane z = c.z, split into n x n quads, facing +z.
void add_square(SheetContent& content, SheetFrame& f, Vec3 c, double side, int n) {
  const int first = int(f.cloth.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) f.cloth.push_back({c.x + side * (double(i) / n - 0.5), c.y + side * (double(j) / n - 0.5), c.z});
  if (!content.cloth_triangles.empty() && &f != &content.frames[0]) return;  // the same triangles for every frame
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = first + j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
      content.cloth_triangles.push_back({a, b, e});
      content.cloth_triangles.push_back({a, e, d});
      content.triangle_colour.insert(content.triangle_colour.end(), 2, 0);
    }
}

SheetView front_view() {
  SheetView v;
  v.angle = SheetAngle::front;
  return v;
}

TEST(WEFT_TEST_SUITE, sheet_depth_test_hides_a_collider_behind_cloth) {
  const ScratchDir dir("sheet_depth");
  SheetContent c;
  c.frames.resize(2);
  c.frames[1].frame = 1;
  add_square(c, c.frames[0], {0, 0, 0}, 0.5, 1);
  add_square(c, c.frames[1], {0, 0, 0}, 0.5, 1);
  c.collider_triangles = {{0, 1, 2}};
  // Frame 0: a long collider triangle behind the cloth wherever the cloth covers it, but leaning towards the
  // camera further up, out of the cell, so that its centre is in front: sorting by depth draws it on top.
  c.frames[0].collider = {{-0.15, -0.15, -0.05}, {0.15, -0.15, -0.05}, {0, 10, 0.8}};
  // Frame 1: a small one in front of the cloth.
  c.frames[1].collider = {{-0.1, -0.1, 0.05}, {0.1, -0.1, 0.05}, {0, 0.1, 0.05}};
  const std::string png = dir.file("sheet.png");
  const int cell = 200;
  write_contact_sheet(png, c, 2, cell, front_view());
  const Image im(png);
  ASSERT_EQ(im.width, 2 * cell);

  const Box cloth = find(im, 0, cell, red);
  ASSERT_GT(cloth.width(), cell / 2);
  EXPECT_NEAR(cloth.width(), cloth.height(), 3);  // a square, front on
  int grey_inside = 0;
  for (int y = cloth.y0 + 2; y <= cloth.y1 - 2; ++y)
    for (int x = cloth.x0 + 2; x <= cloth.x1 - 2; ++x) grey_inside += grey(im.at(x, y));
  EXPECT_EQ(grey_inside, 0);
  EXPECT_GT(find(im, 0, cell, grey).count, 100);  // above the cloth, the collider shows

  const Box front = find(im, 1, cell, grey);
  EXPECT_GT(front.count, 1000);  // a 0.2 m triangle in front of the 0.5 m cloth
  const Box cloth1 = find(im, 1, cell, red);
  EXPECT_TRUE(grey(im.at((cloth1.x0 + cloth1.x1) / 2, (cloth1.y0 + cloth1.y1) / 2)));
  EXPECT_GT(front.x0, cloth1.x0);
  EXPECT_LT(front.x1, cloth1.x1);
}

TEST(WEFT_TEST_SUITE, sheet_has_no_cracks_between_cloth_triangles) {
  const ScratchDir dir("sheet_cracks");
  SheetContent c;
  c.frames.resize(1);
  add_square(c, c.frames[0], {0.01, 0.02, 0}, 0.5, 70);  // small triangles, edges off the sample grid
  c.collider_triangles = {{0, 1, 2}, {0, 2, 3}};       // a large wall behind
  c.frames[0].collider = {{-2, -2, -0.2}, {2, -2, -0.2}, {2, 2, -0.2}, {-2, 2, -0.2}};
  const std::string png = dir.file("sheet.png");
  write_contact_sheet(png, c, 1, 180, front_view());
  const Image im(png);
  const Box cloth = find(im, 0, 180, red);
  ASSERT_GT(cloth.width(), 90);
  EXPECT_EQ(cloth.count, cloth.width() * cloth.height());  // every pixel of the square is cloth
}

TEST(WEFT_TEST_SUITE, sheet_lights_both_sides_of_the_cloth_apart) {
  const ScratchDir dir("sheet_sides");
  SheetContent c;
  c.frames.resize(2);
  add_square(c, c.frames[0], {0, 0, 0}, 0.5, 2);
  add_square(c, c.frames[1], {0, 0, 0}, 0.5, 2);
  for (Vec3& p : c.frames[1].cloth) p = {-p.x, p.y, -p.z};  // turned round: its back faces the camera
  for (SheetAngle angle : {SheetAngle::front, SheetAngle::standard, SheetAngle::three_quarter}) {
    SheetView view;
    view.angle = angle;
    const std::string png = dir.file("sheet.png");
    write_contact_sheet(png, c, 2, 120, view);
    const Image im(png);
    const Rgb8 outside = im.at(60, kTitle + 74), inside = im.at(180, kTitle + 74);
    EXPECT_TRUE(red(outside)) << int(angle);
    EXPECT_TRUE(red(inside)) << int(angle);  // lit, not black
    EXPECT_GT(inside.r, 70) << int(angle);
    EXPECT_LT(inside.r + inside.g + inside.b, outside.r + outside.g + outside.b - 30) << int(angle);  // darker
  }
}

TEST(WEFT_TEST_SUITE, sheet_frames_the_cloth_not_the_ground) {
  const ScratchDir dir("sheet_framing");
  SheetContent c;
  c.frames.resize(1);
  add_square(c, c.frames[0], {0, 0.35, 0}, 0.5, 4);
  c.collider_triangles = {{0, 1, 2}, {0, 2, 3}};  // a 10 m ground plane
  c.frames[0].collider = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  const int cell = 200;
  const std::string png = dir.file("sheet.png");
  write_contact_sheet(png, c, 1, cell);
  const Box cloth = find(Image(png), 0, cell, red);
  EXPECT_GT(std::max(cloth.width(), cloth.height()), 0.7 * cell);
  EXPECT_GT(std::min(cloth.width(), cloth.height()), 0.5 * cell);
  EXPECT_GT(find(Image(png), 0, cell, grey).count, 1000);  // the ground, cut off by the cell

  SheetView all;
  all.frame_all = true;
  write_contact_sheet(png, c, 1, cell, all);
  const Box small = find(Image(png), 0, cell, red);
  EXPECT_LT(std::max(small.width(), small.height()), 0.15 * cell);
  all.zoom = 3;
  write_contact_sheet(png, c, 1, cell, all);
  const Box zoomed = find(Image(png), 0, cell, red);
  EXPECT_NEAR(zoomed.width(), 3 * small.width(), 4);
}

TEST(WEFT_TEST_SUITE, sheet_is_the_same_bytes_twice) {
  const ScratchDir dir("sheet_bytes");
  SheetContent c;
  c.title = "twice";
  c.frames.resize(3);
  for (int f = 0; f < 3; ++f) {
    c.frames[f].frame = f + 1;
    add_square(c, c.frames[f], {0, 0.4, 0}, 0.6, 24);
    for (Vec3& p : c.frames[f].cloth) p.z = 0.1 * std::sin(7 * p.x + f) * std::cos(5 * p.y);  // folds
    c.frames[f].collider = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {0, 0.4, -0.02}};
  }
  for (size_t i = 0; i < c.triangle_colour.size(); ++i) c.triangle_colour[i] = int(i / 300);
  c.collider_triangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};
  write_contact_sheet(dir.file("a.png"), c, 2, 150);
  write_contact_sheet(dir.file("b.png"), c, 2, 150);
  const std::string a = dir.read("a.png");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, dir.read("b.png"));
}

}  // namespace
