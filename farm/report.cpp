#include "farm/report.hpp"

#include "backends/simulation.hpp"
#include "core/hash.hpp"
#include "io/cache_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/scene_source.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace weft::farm {
namespace {

namespace fs = std::filesystem;

int read_exit_code(const Task& t) {
  std::ifstream in(t.exit_file());
  int code = -1;
  if (!(in >> code)) return -1;
  return code;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

// The settings a batch's wedges vary, in the order they first appear: the summary's extra columns.
std::vector<std::string> wedge_columns(const Batch& b) {
  std::vector<std::string> cols;
  for (const Task& t : b.tasks)
    for (const io::SceneOverride& o : t.wedge)
      if (std::find(cols.begin(), cols.end(), o.name) == cols.end()) cols.push_back(o.name);
  return cols;
}

std::string wedge_value(const Task& t, const std::string& name) {
  for (const io::SceneOverride& o : t.wedge)
    if (o.name == name) return o.value;
  return "";
}

std::string html_escape(const std::string& s) {
  std::string r;
  for (char c : s) r += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return r;
}

// A task the queue has no word on: what its exit status and cache say.
std::string ended_state(const TaskStatus& s) {
  if (s.exit_code == 0 && s.frames_planned > 0 && s.frames_done == s.frames_planned) return "done";
  if (s.exit_code == 130 || s.exit_code == 143) return "stopped";
  if (s.exit_code > 0) return "failed";
  return s.frames_done > 0 ? "incomplete" : "not started";
}

struct Row {
  std::vector<std::string> cells;
};

}  // namespace

std::string hash_text(uint64_t h) { return hash_hex(h); }

std::vector<TaskStatus> batch_status(const Batch& b, const std::map<int, std::string>& queue) {
  std::vector<TaskStatus> out;
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const Task& t = b.tasks[k];
    TaskStatus s;
    s.exit_code = read_exit_code(t);
    int first = 0, last = 0;
    if (io::parse_frame_range(t.frames, first, last)) s.frames_planned = last - first + 1;
    if (fs::exists(t.cache())) {
      try {
        const io::CacheReader c(t.cache());
        s.frames_done = c.frame_count();
        s.frames_planned = c.header().settings.frame_end - c.header().settings.frame_start + 1;
      } catch (const std::exception&) {
        s.state = "unreadable cache";
      }
    }
    // The queue knows best while a task runs, and when it ended without a word of its own (cancelled, out of
    // time, a node failure); a task that ran to its end has its exit code and its cache.
    const auto q = queue.find(int(k));
    const bool queued = q != queue.end() && q->second != "COMPLETED" && q->second != "FAILED";
    if (queued)
      s.state = lower(q->second);
    else if (s.state.empty())  // not "unreadable cache"
      s.state = ended_state(s);
    out.push_back(s);
  }
  return out;
}

std::vector<TaskSummary> collect(const Batch& b, Backend backend, bool sheets) {
  const std::vector<TaskStatus> status = batch_status(b, {});
  std::vector<TaskSummary> out;
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const Task& t = b.tasks[k];
    TaskSummary s;
    s.status = status[k];
    if (s.status.frames_done > 0) {
      const io::CacheReader c(t.cache());
      const std::vector<FrameStats>& stats = c.stats();
      double seconds = 0;
      for (size_t f = 1; f < stats.size(); ++f) seconds += stats[f].seconds;  // stored frame 0: the initial state
      if (stats.size() > 1) s.ms_per_frame = 1e3 * seconds / double(stats.size() - 1);
      for (const FrameStats& fs : stats) s.max_strain = std::max(s.max_strain, double(fs.max_strain));
      s.hash = io::cache_hash(c);
      Scene scene = io::load_scene(t.scene, io::BuiltinOptions{t.res});
      scene.settings.frame_start = c.header().settings.frame_start;
      scene.settings.frame_end = c.header().settings.frame_end;
      io::apply_overrides(scene, t.set);
      const int last = c.frame_count() - 1;
      auto sim = make_simulation(backend, scene);
      sim->set_state(c.frames()[size_t(last)], c.positions(last), c.velocities(last));
      s.intersections = sim->intersections();
      s.p99_strain = sim->strain_quantile(0.99);
      if (sheets) {
        io::SheetContent content = io::cache_sheet(c, &scene, c.frames().front(), c.frames().back(), 4);
        content.title = t.name;
        for (const io::SceneOverride& o : t.wedge) content.title += "  " + o.name + "=" + o.value;
        io::write_contact_sheet(t.sheet(), content, 4, 200);
        s.sheet = true;
      }
    }
    out.push_back(s);
  }

  // The table, as Markdown and as HTML: one row per task, the wedge's settings as columns.
  const std::vector<std::string> cols = wedge_columns(b);
  std::vector<std::string> head{"task"};
  head.insert(head.end(), cols.begin(), cols.end());
  for (const char* h : {"state", "frames", "ms/frame", "max strain", "p99 strain (last)", "intersections (last)", "hash"})
    head.push_back(h);
  std::vector<Row> rows;
  for (size_t k = 0; k < b.tasks.size(); ++k) {
    const Task& t = b.tasks[k];
    const TaskSummary& s = out[k];
    Row r;
    r.cells.push_back(t.name);
    for (const std::string& c : cols) r.cells.push_back(wedge_value(t, c));
    const bool has = s.status.frames_done > 0;
    r.cells.push_back(s.status.state);
    r.cells.push_back(std::to_string(s.status.frames_done) + "/" +
                      (s.status.frames_planned > 0 ? std::to_string(s.status.frames_planned) : "?"));
    r.cells.push_back(has ? fixed(s.ms_per_frame, 1) : "");
    r.cells.push_back(has ? fixed(s.max_strain, 3) : "");
    r.cells.push_back(has ? fixed(s.p99_strain, 3) : "");
    r.cells.push_back(has ? std::to_string(s.intersections) : "");
    r.cells.push_back(has ? hash_text(s.hash) : "");
    rows.push_back(r);
  }

  const std::string md_path = b.output + "/summary.md", html_path = b.output + "/summary.html";
  fs::create_directories(b.output);
  {
    std::ofstream md(md_path + ".tmp");
    md << "# weft batch " << b.name << "\n\n" << b.tasks.size() << " tasks from `" << b.file << "`.\n\n|";
    for (const std::string& h : head) md << " " << h << " |";
    md << "\n|";
    for (size_t i = 0; i < head.size(); ++i) md << (i == 0 ? " --- |" : " ---: |");
    md << "\n";
    for (const Row& r : rows) {
      md << "|";
      for (const std::string& c : r.cells) md << " " << c << " |";
      md << "\n";
    }
    md << "\n";
    for (size_t k = 0; k < b.tasks.size(); ++k)
      if (out[k].sheet) md << "![" << b.tasks[k].name << "](" << b.tasks[k].name << "/sheet.png)\n";
    if (!md) throw std::runtime_error(md_path + ": cannot write");
  }
  fs::rename(md_path + ".tmp", md_path);
  {
    std::ofstream h(html_path + ".tmp");
    h << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>weft batch " << html_escape(b.name)
      << "</title>\n<style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}"
         "td,th{border:1px solid #ccc;padding:.25em .6em;text-align:right}td:first-child{text-align:left}"
         ".row{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0}figcaption{font-size:90%}"
         "img{max-width:100%}</style></head><body>\n"
      << "<h1>weft batch " << html_escape(b.name) << "</h1>\n<p>" << b.tasks.size() << " tasks from <code>"
      << html_escape(b.file) << "</code>.</p>\n<table><tr>";
    for (const std::string& c : head) h << "<th>" << html_escape(c) << "</th>";
    h << "</tr>\n";
    for (const Row& r : rows) {
      h << "<tr>";
      for (const std::string& c : r.cells) h << "<td>" << html_escape(c) << "</td>";
      h << "</tr>\n";
    }
    h << "</table>\n";
    // One section per wedge (and one for the single tasks): their contact sheets side by side.
    std::vector<std::string> groups;
    for (const Task& t : b.tasks)
      if (std::find(groups.begin(), groups.end(), t.wedge_name) == groups.end()) groups.push_back(t.wedge_name);
    for (const std::string& g : groups) {
      h << "<h2>" << (g.empty() ? std::string("tasks") : "wedge " + html_escape(g)) << "</h2>\n<div class=\"row\">\n";
      for (size_t k = 0; k < b.tasks.size(); ++k) {
        const Task& t = b.tasks[k];
        if (t.wedge_name != g || !out[k].sheet) continue;
        std::string caption = t.name;
        for (const io::SceneOverride& o : t.wedge) caption += "  " + o.name + "=" + o.value;
        h << "<figure><img src=\"" << html_escape(t.name) << "/sheet.png\" width=\"800\"><figcaption>"
          << html_escape(caption) << ": max strain " << fixed(out[k].max_strain, 3) << ", "
          << out[k].intersections << " intersections, " << fixed(out[k].ms_per_frame, 1)
          << " ms/frame</figcaption></figure>\n";
      }
      h << "</div>\n";
    }
    h << "</body></html>\n";
    if (!h) throw std::runtime_error(html_path + ": cannot write");
  }
  fs::rename(html_path + ".tmp", html_path);
  return out;
}

}  // namespace weft::farm
