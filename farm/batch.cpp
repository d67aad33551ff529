#include "farm/batch.hpp"

#include "core/error.hpp"
#include "io/cache_file.hpp"
#include "io/scene_source.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

namespace weft::farm {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // a wedge's settings vary in the order they are written

// Errors name the file and where in it: "batch.json: tasks[1] (name): what".
struct Where {
  const std::string& file;
  std::string path;
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file + ": " + (path.empty() ? "top level" : path) + ": " + what);
  }
  Where at(const std::string& key) const { return {file, path.empty() ? key : path + "." + key}; }
};

void only_keys(const json& j, const Where& w, std::initializer_list<const char*> known) {
  if (!j.is_object()) w.fail("expected an object {...}");
  for (const auto& item : j.items()) {
    bool ok = false;
    std::string list;
    for (const char* k : known) {
      ok = ok || item.key() == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!ok) w.at(item.key()).fail("unknown key (known here: " + list + ")");
  }
}

std::string string_at(const json& j, const char* key, const Where& w, const std::string& fallback = "") {
  if (!j.contains(key)) return fallback;
  if (!j.at(key).is_string()) w.at(key).fail("expected a string");
  return j.at(key).get<std::string>();
}

int int_at(const json& j, const char* key, const Where& w, int lo, int fallback) {
  if (!j.contains(key)) return fallback;
  const json& v = j.at(key);
  if (!v.is_number_integer() || v.get<long>() < lo || v.get<long>() > (1L << 30))
    w.at(key).fail("expected an integer >= " + std::to_string(lo));
  return v.get<int>();
}

// A setting's value as the command line writes it: 12, 0.5, on, proximity, 0,-9.81,0.
std::string value_text(const json& v, const Where& w) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "on" : "off";
  if (v.is_number()) return v.dump();
  if (v.is_array() && v.size() == 3) {
    std::string t;
    for (const json& c : v) {
      if (!c.is_number()) w.fail("expected [x, y, z] numbers");
      t += (t.empty() ? "" : ",") + c.dump();
    }
    return t;
  }
  w.fail("expected a number, a string, true/false or [x, y, z], got " + v.dump());
}

io::SceneOverride checked(const std::string& name, const std::string& value, const Where& w) {
  io::SceneOverride o{name, value};
  try {
    io::check_override(o);
  } catch (const InputError& e) {
    w.fail(e.what());
  }
  return o;
}

bool plain_name(const std::string& s) {
  if (s.empty() || s[0] == '.' || s[0] == '-') return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) return false;
  return true;
}

std::string absolute(const fs::path& base, const std::string& p) {
  return fs::weakly_canonical(fs::path(p).is_absolute() ? fs::path(p) : base / p).string();
}

void read_slurm(const json& j, const Where& w, SlurmOptions& s) {
  only_keys(j, w, {"partition", "time", "gpus_per_task", "cpus_per_task", "max_parallel", "sbatch_args"});
  s.partition = string_at(j, "partition", w);
  s.time = string_at(j, "time", w);
  s.gpus_per_task = int_at(j, "gpus_per_task", w, 0, 0);
  s.cpus_per_task = int_at(j, "cpus_per_task", w, 0, 0);
  s.max_parallel = int_at(j, "max_parallel", w, 0, 0);
  if (j.contains("sbatch_args")) {
    const json& a = j.at("sbatch_args");
    if (!a.is_array()) w.at("sbatch_args").fail("expected an array of strings");
    for (const json& x : a) {
      if (!x.is_string()) w.at("sbatch_args").fail("expected an array of strings");
      s.sbatch_args.push_back(x.get<std::string>());
    }
  }
}

// One entry of "tasks": a task, or a wedge expanded into tasks named <name>-<k>.
void read_task(const json& j, const Where& w, const fs::path& base, Batch& b) {
  if (!j.is_object()) w.fail("expected an object {...}");
  if (!j.contains("name")) w.fail("missing key 'name'");
  Task t;
  t.name = string_at(j, "name", w);
  const Where wt{w.file, w.path + " (" + t.name + ")"};
  only_keys(j, wt, {"name", "scene", "res", "frames", "set", "wedge", "combine"});
  if (!plain_name(t.name)) wt.at("name").fail("a task name is a folder name: letters, digits, '-', '_', '.'");
  t.scene = string_at(j, "scene", wt);
  if (t.scene.empty()) wt.fail("missing key 'scene' (builtin:NAME, a .json or a .h5 scene)");
  if (t.scene.rfind("builtin:", 0) != 0) {
    t.scene = absolute(base, t.scene);
    if (!fs::exists(t.scene)) wt.at("scene").fail(t.scene + " does not exist");
  }
  t.res = int_at(j, "res", wt, 1, 0);
  if (t.res > 0 && t.scene.rfind("builtin:", 0) != 0) wt.at("res").fail("'res' applies to a built-in scene");
  t.frames = string_at(j, "frames", wt);
  int first = 0, last = 0;
  if (!t.frames.empty() && !io::parse_frame_range(t.frames, first, last))
    wt.at("frames").fail("expected \"A-B\" with A <= B, got '" + t.frames + "'");
  if (j.contains("set")) {
    const json& set = j.at("set");
    if (!set.is_object()) wt.at("set").fail("expected an object {\"name\": value}");
    for (const auto& item : set.items()) {
      const Where wi = wt.at("set").at(item.key());
      t.set.push_back(checked(item.key(), value_text(item.value(), wi), wi));
    }
  }

  if (!j.contains("wedge")) {
    if (j.contains("combine")) wt.at("combine").fail("'combine' belongs to a wedge");
    b.tasks.push_back(t);
    return;
  }
  // A wedge: each setting's values; the tasks are their product, or (combine "list") the k-th values together.
  const json& wedge = j.at("wedge");
  const Where ww = wt.at("wedge");
  if (!wedge.is_object() || wedge.empty()) ww.fail("expected an object {\"setting\": [values]}");
  const std::string combine = string_at(j, "combine", wt, "product");
  if (combine != "product" && combine != "list") wt.at("combine").fail("expected \"product\" or \"list\"");
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> values;
  for (const auto& item : wedge.items()) {
    const Where wi = ww.at(item.key());
    if (!item.value().is_array() || item.value().empty()) wi.fail("expected a non-empty array of values");
    names.push_back(item.key());
    values.emplace_back();
    for (size_t k = 0; k < item.value().size(); ++k) {
      const Where wk{wi.file, wi.path + "[" + std::to_string(k) + "]"};
      values.back().push_back(checked(item.key(), value_text(item.value()[k], wk), wk).value);
    }
    if (combine == "list" && values.back().size() != values.front().size())
      wi.fail("has " + std::to_string(values.back().size()) + " values, '" + names.front() + "' " +
              std::to_string(values.front().size()) + " (combine \"list\" takes the k-th value of each)");
  }
  size_t count = 1;
  if (combine == "list") {
    count = values.front().size();
  } else {
    for (const auto& v : values) count *= v.size();
    if (count > 100000) ww.fail("expands to " + std::to_string(count) + " tasks");
  }
  const int digits = int(std::to_string(count - 1).size());
  for (size_t k = 0; k < count; ++k) {
    Task wt_k = t;
    std::string index = std::to_string(k);
    wt_k.name = t.name + "-" + std::string(size_t(digits) - index.size(), '0') + index;
    wt_k.wedge_name = t.name;
    size_t rest = k;  // product: the first setting varies slowest
    for (size_t s = names.size(); s-- > 0;) {
      const size_t pick = combine == "list" ? k : rest % values[s].size();
      if (combine != "list") rest /= values[s].size();
      wt_k.wedge.insert(wt_k.wedge.begin(), {names[s], values[s][pick]});
    }
    wt_k.set.insert(wt_k.set.end(), wt_k.wedge.begin(), wt_k.wedge.end());
    b.tasks.push_back(wt_k);
  }
}

}  // namespace

Batch read_batch(const std::string& path, const std::string& executable) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    const std::string what = e.what();
    const size_t tag = what.find("] ");
    throw InputError(path + ": " + (tag == std::string::npos ? what : what.substr(tag + 2)));
  }
  const Where w{path, ""};
  only_keys(j, w, {"name", "output", "backend", "threads", "executable", "tasks", "slurm"});
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  Batch b;
  b.file = path;
  b.name = string_at(j, "name", w, fs::path(path).stem().string());
  if (!plain_name(b.name)) w.at("name").fail("a batch name is a word: letters, digits, '-', '_', '.'");
  b.output = absolute(base, string_at(j, "output", w, b.name));
  b.backend = string_at(j, "backend", w);
  if (!b.backend.empty() && b.backend != "serial" && b.backend != "openmp" && b.backend != "cuda")
    w.at("backend").fail("expected serial, openmp or cuda");
  b.threads = int_at(j, "threads", w, 0, 0);
  b.executable = j.contains("executable") ? absolute(base, string_at(j, "executable", w)) : executable;
  if (j.contains("slurm")) read_slurm(j.at("slurm"), w.at("slurm"), b.slurm);
  if (!j.contains("tasks") || !j.at("tasks").is_array() || j.at("tasks").empty())
    w.at("tasks").fail("expected a non-empty array of tasks");
  const json& tasks = j.at("tasks");
  for (size_t i = 0; i < tasks.size(); ++i) read_task(tasks[i], {path, "tasks[" + std::to_string(i) + "]"}, base, b);
  std::set<std::string> seen;
  for (Task& t : b.tasks) {
    if (!seen.insert(t.name).second) w.at("tasks").fail("two tasks are named '" + t.name + "'");
    t.dir = b.output + "/" + t.name;
  }
  return b;
}

std::vector<std::string> task_command(const Batch& b, const Task& t) {
  std::vector<std::string> c{b.executable};
  if (!b.backend.empty()) c.insert(c.end(), {"--backend", b.backend});
  if (b.threads > 0) c.insert(c.end(), {"--threads", std::to_string(b.threads)});
  c.insert(c.end(), {"run", t.scene});
  if (t.res > 0) c.insert(c.end(), {"--res", std::to_string(t.res)});
  if (!t.frames.empty()) c.insert(c.end(), {"--frames", t.frames});
  for (const io::SceneOverride& o : t.set) c.insert(c.end(), {"--set", o.name + "=" + o.value});
  c.insert(c.end(), {"-o", t.cache(), "--resume", "--hash"});
  return c;
}

std::string cache_conflict(const Task& t) {
  if (!fs::exists(t.cache())) return "";
  try {
    const io::CacheReader c(t.cache());
    Scene s = io::load_scene(t.scene, io::BuiltinOptions{t.res});
    int first = 0, last = 0;
    if (!t.frames.empty() && io::parse_frame_range(t.frames, first, last)) {
      s.settings.frame_start = first;
      s.settings.frame_end = last;
    }
    io::apply_overrides(s, t.set);
    const io::CacheHeader run{s.name, "", s.points.size(), s.triangles, s.settings, io::overrides_text(t.set)};
    const std::string why = io::resume_mismatch(c, run, s.points.position);
    if (!why.empty()) return t.cache() + " belongs to another run (scene " + c.header().scene + "): " + why;
  } catch (const std::exception& e) {
    return t.cache() + " cannot be read: " + e.what();
  }
  return "";
}

std::string shell_quote(const std::string& word) {
  bool plain = !word.empty();
  for (char c : word)
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_./:=,@%+", c) != nullptr);
  if (plain) return word;
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string shell_line(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& w : words) line += (line.empty() ? "" : " ") + shell_quote(w);
  return line;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

void write_submission(const Batch& b, const Submission& s) {
  const json j = {{"scheduler", s.scheduler}, {"job", s.job}, {"script", s.script}, {"time", s.time},
                  {"tasks", [&] {
                     json names = json::array();
                     for (const Task& t : b.tasks) names.push_back(t.name);
                     return names;
                   }()}};
  const std::string path = b.submission_file(), tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error(tmp + ": cannot write");
  }
  fs::rename(tmp, path);
}

bool read_submission(const Batch& b, Submission& s) {
  std::ifstream in(b.submission_file());
  if (!in) return false;
  try {
    const json j = json::parse(in);
    s.scheduler = j.value("scheduler", "");
    s.job = j.value("job", "");
    s.script = j.value("script", "");
    s.time = j.value("time", "");
  } catch (const json::exception& e) {
    throw InputError(b.submission_file() + ": " + e.what());
  }
  return true;
}

}  // namespace weft::farm
