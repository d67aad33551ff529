#include "io/scene_source.hpp"

#include "core/error.hpp"
#include "io/json_scene.hpp"
#include "io/scene_file.hpp"

#include <cstdio>

namespace weft::io {
namespace {

bool has_suffix(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Scene load_scene(const std::string& spec, const BuiltinOptions& opt) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) return make_builtin_scene(spec.substr(prefix.size()), opt);
  const bool json = has_suffix(spec, ".json"), h5 = has_suffix(spec, ".h5");
  if ((json || h5) && opt.res > 0)
    throw InputError(spec + ": --res sets the resolution of a built-in scene; a scene file has its own");
  if (json) return read_json_scene(spec);
  if (h5) return read_scene(spec);
  throw InputError(spec + ": unknown scene source (use builtin:NAME, a .json scene or a .h5 scene file; built-in: " +
                   [] {
                     std::string k;
                     for (const auto& n : builtin_scene_names()) k += (k.empty() ? "" : ", ") + n;
                     return k;
                   }() +
                   ")");
}

bool parse_frame_range(const std::string& text, int& first, int& last) {
  int a = 0, b = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d-%d%c", &a, &b, &extra) != 2 || b < a) return false;
  first = a;
  last = b;
  return true;
}

}  // namespace weft::io
