#include "io/contact_sheet.hpp"

#include "io/trimesh.hpp"
#include "scene/collider_set.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace weft::io {
namespace {

struct Rgb { double r, g, b; };
// One colour per layer (or piece), distinct on a white background; colliders in grey.
const Rgb kPalette[] = {{0.84, 0.30, 0.25}, {0.95, 0.66, 0.20}, {0.27, 0.55, 0.80}, {0.35, 0.70, 0.40},
                        {0.62, 0.42, 0.75}, {0.20, 0.70, 0.70}, {0.90, 0.50, 0.65}, {0.55, 0.45, 0.30}};
const Rgb kBody{0.62, 0.62, 0.64};
constexpr uint32_t kWhite = 0xffffff;
constexpr int kSuper = 2;  // samples per pixel along each axis

// An orthographic camera looking at the origin from `back` (which points from the scene to the camera).
struct Camera {
  Vec3 right, up, back;
  explicit Camera(SheetAngle angle) {
    double az = 0.45, el = 0.22;  // standard: a little from the side and above the front (+z)
    switch (angle) {
      case SheetAngle::standard: break;
      case SheetAngle::front: az = 0, el = 0; break;
      case SheetAngle::side: az = pi / 2, el = 0; break;
      case SheetAngle::top: az = 0, el = pi / 2; break;
      case SheetAngle::three_quarter: az = pi / 4, el = 25 * pi / 180; break;
    }
    back = {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
    right = {std::cos(az), 0, -std::sin(az)};
    up = cross(back, right);  // from the top, the front (+z) is at the bottom of the cell
  }
};

struct Framing { double cx, cy, scale; };  // the centre on the view plane (along right, up) and pixels per metre

// The same framing for every cell: every frame's cloth (and with frame_all the colliders) fits the part of
// the cell below the label, with a margin, before the zoom.
Framing frame_view(const SheetContent& c, const Camera& cam, const SheetView& view, int cell_px, int label_px) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const auto add = [&](const std::vector<Vec3>& pts) {
    for (const Vec3& p : pts) {
      const double x = dot(p, cam.right), y = dot(p, cam.up);
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  };
  for (const SheetFrame& f : c.frames) add(f.cloth);
  if (view.frame_all || x1 < x0)  // no cloth: frame the colliders
    for (const SheetFrame& f : c.frames) add(f.collider);
  if (x1 < x0) return {0, 0, view.zoom};
  const double margin = std::max(4, cell_px / 20);
  const double room_x = std::max(1.0, cell_px - 2 * margin), room_y = std::max(1.0, cell_px - label_px - 2 * margin);
  double scale = std::min(x1 - x0 > 1e-9 ? room_x / (x1 - x0) : 1e300, y1 - y0 > 1e-9 ? room_y / (y1 - y0) : 1e300);
  if (scale == 1e300) scale = room_y;  // a single point: a metre fills the cell
  return {(x0 + x1) / 2, (y0 + y1) / 2, scale * view.zoom};
}

// Flat shading from a light near the camera (diffuse plus ambient), two-sided: a triangle whose back faces
// the camera is lit with its normal flipped, and cloth seen from its back (`tint_back`) is drawn darker.
uint32_t shade(Rgb base, Vec3 a, Vec3 b, Vec3 c, const Camera& cam, Vec3 light, bool tint_back) {
  Vec3 n = cross(b - a, c - a);
  const double len = std::sqrt(double(dot(n, n)));
  const bool back_faces = dot(n, cam.back) < 0;
  if (back_faces) n = -n;
  const double d = len > 0 ? std::max(0.0, double(dot(n, light)) / len) : 0;
  double k = 0.35 + 0.65 * d;
  if (back_faces && tint_back) k *= 0.72;
  const auto byte = [k](double v) { return uint32_t(std::clamp(std::lround(v * k * 255), 0L, 255L)); };
  return byte(base.r) << 16 | byte(base.g) << 8 | byte(base.b);
}

// A cell's samples, kSuper x kSuper per pixel: colour (0xRRGGBB) and depth (larger is nearer the camera).
struct Raster {
  int size = 0;  // samples per side
  std::vector<uint32_t> colour;
  std::vector<float> depth;
  void clear(int n) {
    size = n;
    colour.assign(size_t(n) * n, kWhite);
    depth.assign(size_t(n) * n, -std::numeric_limits<float>::infinity());
  }
};

struct Screen { double x, y, z; };  // sample coordinates (x right, y down, sample centres at +0.5); depth

// The edge i -> j as e(x, y) = a x + b y + c (positive on its left when y points up), computed from its points
// in a canonical order (lower index first) and negated for the other direction: the two triangles sharing an
// edge evaluate exactly opposite values, so a sample on the edge belongs to both and none falls between.
struct Edge { double a, b, c; };
Edge edge(const Screen* p, int i, int j) {
  const bool flip = j < i;
  const Screen& P = p[flip ? j : i];
  const Screen& Q = p[flip ? i : j];
  const Edge e{-(Q.y - P.y), Q.x - P.x, (Q.y - P.y) * P.x - (Q.x - P.x) * P.y};
  return flip ? Edge{-e.a, -e.b, -e.c} : e;
}

// The first and last sample index whose centre lies in [lo, hi], clamped to the raster.
int first_sample(double lo, int n) { return int(std::clamp(std::ceil(lo - 0.5), 0.0, double(n))); }
int last_sample(double hi, int n) { return int(std::clamp(std::floor(hi - 0.5), -1.0, double(n - 1))); }

// Depth-tested fill of one triangle: a sample takes the colour where the triangle's depth there, plus `bias`,
// is nearer than what the sample holds (ties: the first drawn stays).
void fill(Raster& r, const Screen* p, const std::array<int, 3>& t, uint32_t rgb, double bias) {
  const Screen &A = p[t[0]], &B = p[t[1]], &C = p[t[2]];
  const double area = (B.x - A.x) * (C.y - A.y) - (B.y - A.y) * (C.x - A.x);
  if (!(area != 0) || !std::isfinite(area) || !std::isfinite(A.z + B.z + C.z)) return;  // edge-on, or not finite
  const int x0 = first_sample(std::min({A.x, B.x, C.x}), r.size), x1 = last_sample(std::max({A.x, B.x, C.x}), r.size);
  const int y0 = first_sample(std::min({A.y, B.y, C.y}), r.size), y1 = last_sample(std::max({A.y, B.y, C.y}), r.size);
  if (x0 > x1 || y0 > y1) return;
  Edge e0 = edge(p, t[1], t[2]), e1 = edge(p, t[2], t[0]), e2 = edge(p, t[0], t[1]);  // opposite A, B, C
  if (area < 0) {  // inside is where all three are >= 0
    e0 = {-e0.a, -e0.b, -e0.c}, e1 = {-e1.a, -e1.b, -e1.c}, e2 = {-e2.a, -e2.b, -e2.c};
  }
  // Depth as a plane over the samples: the edge values are barycentric weights times |area|.
  const double inv = 1 / std::fabs(area);
  const double za = (e0.a * A.z + e1.a * B.z + e2.a * C.z) * inv, zb = (e0.b * A.z + e1.b * B.z + e2.b * C.z) * inv;
  const double zc = (e0.c * A.z + e1.c * B.z + e2.c * C.z) * inv + bias;
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    const double r0 = e0.b * py + e0.c, r1 = e1.b * py + e1.c, r2 = e2.b * py + e2.c, rz = zb * py + zc;
    uint32_t* colour = r.colour.data() + size_t(y) * r.size;
    float* depth = r.depth.data() + size_t(y) * r.size;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      if (e0.a * px + r0 < 0 || e1.a * px + r1 < 0 || e2.a * px + r2 < 0) continue;
      const float z = float(za * px + rz);
      if (z > depth[x]) depth[x] = z, colour[x] = rgb;
    }
  }
}

void project(const std::vector<Vec3>& x, const Camera& cam, const Framing& fr, double cx, double cy,
             std::vector<Screen>& out) {
  const double s = fr.scale * kSuper;
  out.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i)
    out[i] = {cx + (dot(x[i], cam.right) - fr.cx) * s, cy - (dot(x[i], cam.up) - fr.cy) * s, dot(x[i], cam.back)};
}

// Rasterizes one frame into `r` (a whole cell, the label band included): colliders first, pushed back by
// one pixel's depth so that cloth resting on them (closer than a pixel) stays in front; then the cloth, each
// layer (colour index) a fiftieth of a pixel in front of the one below, so that coincident layers do not
// fight.
void render_frame(Raster& r, const SheetContent& c, const SheetFrame& f, const Camera& cam, const Framing& fr,
                  int cell_px, int label_px, std::vector<Screen>& screen) {
  r.clear(cell_px * kSuper);
  const double cx = kSuper * cell_px / 2.0, cy = kSuper * (label_px + (cell_px - label_px) / 2.0);
  const double pixel = 1 / fr.scale;  // metres per pixel
  const Vec3 light = normalized(cam.back + 0.6 * cam.up + 0.3 * cam.right);
  if (!f.collider.empty()) {
    project(f.collider, cam, fr, cx, cy, screen);
    for (const auto& t : c.collider_triangles)
      fill(r, screen.data(), t, shade(kBody, f.collider[t[0]], f.collider[t[1]], f.collider[t[2]], cam, light, false),
           -pixel);
  }
  project(f.cloth, cam, fr, cx, cy, screen);
  constexpr size_t colours = sizeof kPalette / sizeof kPalette[0];
  for (size_t i = 0; i < c.cloth_triangles.size(); ++i) {
    const auto& t = c.cloth_triangles[i];
    const int colour = c.triangle_colour[i];
    fill(r, screen.data(), t, shade(kPalette[size_t(colour) % colours], f.cloth[t[0]], f.cloth[t[1]], f.cloth[t[2]], cam, light, true),
         0.02 * pixel * std::clamp(colour, 0, 15));
  }
}

// Averages each pixel's samples into the RGB24 surface data at (ox, oy).
void downsample(const Raster& r, unsigned char* data, int stride, int ox, int oy) {
  const int n = r.size / kSuper;
  for (int y = 0; y < n; ++y) {
    uint32_t* row = reinterpret_cast<uint32_t*>(data + size_t(oy + y) * stride) + ox;
    for (int x = 0; x < n; ++x) {
      uint32_t sr = 0, sg = 0, sb = 0;
      for (int j = 0; j < kSuper; ++j)
        for (int i = 0; i < kSuper; ++i) {
          const uint32_t v = r.colour[size_t(y * kSuper + j) * r.size + x * kSuper + i];
          sr += v >> 16, sg += v >> 8 & 0xff, sb += v & 0xff;
        }
      constexpr uint32_t k = kSuper * kSuper;
      row[x] = (sr + k / 2) / k << 16 | (sg + k / 2) / k << 8 | (sb + k / 2) / k;
    }
  }
}

void draw_label(cairo_t* cr, const SheetFrame& f, double ox, double oy, int label_px) {
  const std::string text = "frame " + std::to_string(f.frame);
  cairo_set_font_size(cr, label_px * 0.6);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.75);  // legible over a collider that reaches into the label band
  cairo_rectangle(cr, ox + 4, oy + label_px * 0.75 + ext.y_bearing - 3, ext.x_advance + 8, ext.height + 6);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_move_to(cr, ox + 8, oy + label_px * 0.75);
  cairo_show_text(cr, text.c_str());
}

cairo_status_t to_stream(void* out, const unsigned char* data, unsigned int length) {
  static_cast<std::ostream*>(out)->write(reinterpret_cast<const char*>(data), length);
  return *static_cast<std::ostream*>(out) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

// Connected pieces of a triangle mesh (union-find over triangle corners), numbered by first appearance.
std::vector<int> triangle_pieces(const std::vector<std::array<int, 3>>& tris, size_t points) {
  std::vector<int> parent(points);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (const auto& t : tris)
    for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
  std::vector<int> id(points, -1), r;
  int next = 0;
  for (const auto& t : tris) {
    int& p = id[find(t[0])];
    if (p < 0) p = next++;
    r.push_back(p);
  }
  return r;
}

}  // namespace

bool parse_sheet_angle(const std::string& name, SheetAngle& angle) {
  static const std::pair<const char*, SheetAngle> names[] = {{"standard", SheetAngle::standard},
                                                              {"front", SheetAngle::front},
                                                              {"side", SheetAngle::side},
                                                              {"top", SheetAngle::top},
                                                              {"three-quarter", SheetAngle::three_quarter}};
  for (const auto& [n, a] : names)
    if (name == n) return angle = a, true;
  return false;
}

void write_contact_sheet(const std::string& path, const SheetContent& content, int columns, int cell_px,
                         const SheetView& view) {
  if (content.frames.empty()) throw std::runtime_error(path + ": a contact sheet needs at least one frame");
  if (content.triangle_colour.size() != content.cloth_triangles.size())
    throw std::runtime_error(path + ": one colour per cloth triangle expected");
  if (!(view.zoom > 0) || !std::isfinite(view.zoom)) throw std::runtime_error(path + ": the zoom must be positive");
  const auto check = [&](const std::vector<std::array<int, 3>>& tris, size_t points, const char* what) {
    for (const auto& t : tris)
      for (int v : t)
        if (v < 0 || size_t(v) >= points)
          throw std::runtime_error(path + ": a " + what + " triangle refers to point " + std::to_string(v) + " of " +
                                   std::to_string(points));
  };
  for (const SheetFrame& f : content.frames) {
    check(content.cloth_triangles, f.cloth.size(), "cloth");
    if (!f.collider.empty()) check(content.collider_triangles, f.collider.size(), "collider");
  }
  if (cell_px < 1) throw std::runtime_error(path + ": the cells need at least one pixel");
  columns = std::max(1, std::min(columns, int(content.frames.size())));
  const int rows = (int(content.frames.size()) + columns - 1) / columns;
  const int title_px = 36, label_px = 28;
  const int width = columns * cell_px, height = title_px + rows * cell_px;
  const std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), cairo_surface_destroy);
  const std::unique_ptr<cairo_t, void (*)(cairo_t*)> cr(cairo_create(surface.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_source_rgb(cr.get(), 0.1, 0.1, 0.1);
  cairo_set_font_size(cr.get(), 18);
  cairo_move_to(cr.get(), 10, 25);
  cairo_show_text(cr.get(), content.title.c_str());
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(path + ": cannot draw the contact sheet: " + cairo_status_to_string(cairo_status(cr.get())));

  // The cells' images go straight into the surface's pixels; Cairo then draws labels and borders over them.
  const Camera cam(view.angle);
  const Framing fr = frame_view(content, cam, view, cell_px, label_px);
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  Raster raster;
  std::vector<Screen> screen;
  for (size_t i = 0; i < content.frames.size(); ++i) {
    render_frame(raster, content, content.frames[i], cam, fr, cell_px, label_px, screen);
    downsample(raster, data, stride, int(i % columns) * cell_px, title_px + int(i / columns) * cell_px);
  }
  cairo_surface_mark_dirty(surface.get());
  for (size_t i = 0; i < content.frames.size(); ++i) {
    const double ox = double(i % columns) * cell_px, oy = title_px + double(i / columns) * cell_px;
    draw_label(cr.get(), content.frames[i], ox, oy, label_px);
    cairo_set_source_rgb(cr.get(), 0.85, 0.85, 0.85);  // cell border
    cairo_set_line_width(cr.get(), 1);
    cairo_rectangle(cr.get(), ox + 0.5, oy + 0.5, cell_px - 1, cell_px - 1);
    cairo_stroke(cr.get());
  }
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(path + ": cannot draw the contact sheet: " + cairo_status_to_string(cairo_status(cr.get())));
  cairo_surface_flush(surface.get());
  write_file_atomically(path, [&](std::ostream& out) {
    const cairo_status_t st = cairo_surface_write_to_png_stream(surface.get(), to_stream, &out);
    if (st != CAIRO_STATUS_SUCCESS) throw std::runtime_error(path + ": cannot write the PNG: " + cairo_status_to_string(st));
  });
}

SheetContent cache_sheet(const CacheReader& cache, const Scene* scene, int first, int last, int count) {
  const CacheHeader& h = cache.header();
  const std::vector<int>& stored = cache.frames();
  if (stored.empty()) throw std::runtime_error(cache.path() + ": the cache holds no frames");
  if (first < stored.front() || last > stored.back() || last < first)
    throw std::runtime_error(cache.path() + " holds frames " + std::to_string(stored.front()) + "-" +
                             std::to_string(stored.back()) + ", not " + std::to_string(first) + "-" +
                             std::to_string(last));
  if (scene && (scene->points.size() != h.points || scene->triangles != h.triangles))
    throw std::runtime_error(cache.path() + ": the cache was not computed from " + scene->name +
                             " (its points or triangles differ)");
  SheetContent c;
  c.cloth_triangles = h.triangles;
  c.title = h.scene + "  (" + std::to_string(h.triangles.size()) + " cloth triangles, " + h.backend + ")";
  if (scene)
    for (const auto& t : h.triangles) c.triangle_colour.push_back(scene->points.layer[t[0]]);
  else
    c.triangle_colour = triangle_pieces(h.triangles, h.points);
  // The collider set; its animations start at the run's first frame and hold their last frame.
  const ColliderSet colliders = scene ? make_collider_set(scene->colliders) : ColliderSet{};
  c.collider_triangles = colliders.triangles;
  count = std::max(1, std::min(count, last - first + 1));
  for (int i = 0; i < count; ++i) {
    const int frame = count == 1 ? last : first + int((long(last - first) * i + (count - 1) / 2) / (count - 1));
    SheetFrame f;
    f.frame = frame;
    f.cloth = cache.positions(frame - stored.front());  // stored frames are consecutive from the first
    if (scene) f.collider = collider_positions(scene->colliders, colliders, std::max(0, frame - h.settings.frame_start));
    c.frames.push_back(std::move(f));
  }
  return c;
}

}  // namespace weft::io
