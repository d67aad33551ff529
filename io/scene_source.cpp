#include "io/scene_source.hpp"

#include "core/error.hpp"

namespace weft::io {

Scene load_scene(const std::string& spec, const BuiltinOptions& opt) {
  const std::string prefix = "builtin:";
  if (spec.rfind(prefix, 0) == 0) return make_builtin_scene(spec.substr(prefix.size()), opt);
  throw InputError(spec + ": unknown scene source (use builtin:NAME; known: " + [] {
    std::string k;
    for (const auto& n : builtin_scene_names()) k += (k.empty() ? "" : ", ") + n;
    return k;
  }() + ")");
}

}  // namespace weft::io
