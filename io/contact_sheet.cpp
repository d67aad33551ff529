#include "io/contact_sheet.hpp"

#include "io/trimesh.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace weft::io {
namespace {

struct Rgb { double r, g, b; };
// One colour per layer (or piece), distinct on a white background; colliders in grey.
const Rgb kPalette[] = {{0.84, 0.30, 0.25}, {0.95, 0.66, 0.20}, {0.27, 0.55, 0.80}, {0.35, 0.70, 0.40},
                        {0.62, 0.42, 0.75}, {0.20, 0.70, 0.70}, {0.90, 0.50, 0.65}, {0.55, 0.45, 0.30}};
const Rgb kBody{0.62, 0.62, 0.64};

// An orthographic camera a little to the side and above the front (+z), looking at the origin.
struct Camera {
  Vec3 right, up, back;  // back points from the scene to the camera
  Camera() {
    const real az = 0.45, el = 0.22;
    back = {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
    right = normalized(Vec3{back.z, 0, -back.x});
    up = cross(back, right);
  }
};

struct Framing { double cx, cy, scale; };

Framing frame_all(const SheetContent& c, const Camera& cam, int cell_px, int label_px) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const auto add = [&](const std::vector<Vec3>& pts) {
    for (const Vec3& p : pts) {
      const double x = dot(p, cam.right), y = dot(p, cam.up);
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  };
  for (const SheetFrame& f : c.frames) { add(f.cloth); add(f.collider); }
  if (x1 < x0) return {0, 0, 1};
  const double room = cell_px - label_px - 16, extent = std::max({x1 - x0, y1 - y0, 1e-9});
  return {(x0 + x1) / 2, (y0 + y1) / 2, room / extent};
}

// Flat shading: a two-sided diffuse term from a light near the camera, plus ambient.
Rgb shade(Rgb base, Vec3 a, Vec3 b, Vec3 c, const Camera& cam) {
  const Vec3 n = cross(b - a, c - a);
  const real len = std::sqrt(dot(n, n));
  const Vec3 light = normalized(cam.back + 0.6 * cam.up + 0.3 * cam.right);
  const double d = len > 0 ? std::fabs(dot(n, light)) / len : 0;
  const double k = 0.35 + 0.65 * d;
  return {base.r * k, base.g * k, base.b * k};
}

struct Triangle { double depth; int index; bool collider; };

// Draws one frame into the cell whose top-left corner is (ox, oy): painter's algorithm, far triangles first.
void draw_frame(cairo_t* cr, const SheetContent& c, const SheetFrame& f, const Camera& cam, const Framing& fr,
                double ox, double oy, int cell_px, int label_px) {
  std::vector<Triangle> order;
  order.reserve(c.cloth_triangles.size() + c.collider_triangles.size());
  const auto depth = [&](const std::vector<Vec3>& x, const std::array<int, 3>& t) {
    return dot(x[t[0]] + x[t[1]] + x[t[2]], cam.back);
  };
  for (size_t i = 0; i < c.cloth_triangles.size(); ++i) order.push_back({depth(f.cloth, c.cloth_triangles[i]), int(i), false});
  if (!f.collider.empty())
    for (size_t i = 0; i < c.collider_triangles.size(); ++i)
      order.push_back({depth(f.collider, c.collider_triangles[i]), int(i), true});
  std::sort(order.begin(), order.end(), [](const Triangle& a, const Triangle& b) {
    return a.depth != b.depth ? a.depth < b.depth : (a.collider != b.collider ? a.collider : a.index < b.index);
  });
  const double cx = ox + cell_px / 2.0, cy = oy + label_px + (cell_px - label_px) / 2.0;
  const auto to_px = [&](Vec3 p, double& x, double& y) {
    x = cx + (dot(p, cam.right) - fr.cx) * fr.scale;
    y = cy - (dot(p, cam.up) - fr.cy) * fr.scale;
  };
  cairo_save(cr);
  cairo_rectangle(cr, ox, oy, cell_px, cell_px);
  cairo_clip(cr);
  cairo_set_line_width(cr, 0.6);  // each triangle also stroked in its colour: no seams between neighbours
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_BEVEL);
  for (const Triangle& t : order) {
    const auto& tri = t.collider ? c.collider_triangles[t.index] : c.cloth_triangles[t.index];
    const std::vector<Vec3>& x = t.collider ? f.collider : f.cloth;
    const Rgb base = t.collider ? kBody
                                : kPalette[size_t(c.triangle_colour[t.index]) % (sizeof kPalette / sizeof kPalette[0])];
    const Rgb col = shade(base, x[tri[0]], x[tri[1]], x[tri[2]], cam);
    double px, py;
    to_px(x[tri[0]], px, py);
    cairo_move_to(cr, px, py);
    for (int k = 1; k < 3; ++k) { to_px(x[tri[k]], px, py); cairo_line_to(cr, px, py); }
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, col.r, col.g, col.b);
    cairo_fill_preserve(cr);
    cairo_stroke(cr);
  }
  cairo_restore(cr);
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_set_font_size(cr, label_px * 0.6);
  cairo_move_to(cr, ox + 8, oy + label_px * 0.75);
  cairo_show_text(cr, ("frame " + std::to_string(f.frame)).c_str());
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

void write_contact_sheet(const std::string& path, const SheetContent& content, int columns, int cell_px) {
  if (content.frames.empty()) throw std::runtime_error(path + ": a contact sheet needs at least one frame");
  if (content.triangle_colour.size() != content.cloth_triangles.size())
    throw std::runtime_error(path + ": one colour per cloth triangle expected");
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

  const Camera cam;
  const Framing fr = frame_all(content, cam, cell_px, label_px);
  for (size_t i = 0; i < content.frames.size(); ++i) {
    const double ox = double(i % columns) * cell_px, oy = title_px + double(i / columns) * cell_px;
    draw_frame(cr.get(), content, content.frames[i], cam, fr, ox, oy, cell_px, label_px);
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
  // Colliders concatenated; their animations start at the run's first frame and hold their last frame.
  if (scene) {
    int off = 0;
    for (const Collider& col : scene->colliders) {
      for (const auto& t : col.triangles) c.collider_triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
      off += col.motion.frames.empty() ? 0 : int(col.motion.frames[0].size());
    }
  }
  count = std::max(1, std::min(count, last - first + 1));
  for (int i = 0; i < count; ++i) {
    const int frame = count == 1 ? last : first + int((long(last - first) * i + (count - 1) / 2) / (count - 1));
    SheetFrame f;
    f.frame = frame;
    f.cloth = cache.positions(frame - stored.front());  // stored frames are consecutive from the first
    if (scene)
      for (const Collider& col : scene->colliders) {
        if (col.motion.frames.empty()) continue;
        const int k = std::clamp(frame - h.settings.frame_start, 0, int(col.motion.frames.size()) - 1);
        f.collider.insert(f.collider.end(), col.motion.frames[k].begin(), col.motion.frames[k].end());
      }
    c.frames.push_back(std::move(f));
  }
  return c;
}

}  // namespace weft::io
