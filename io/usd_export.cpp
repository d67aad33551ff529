#include "io/usd_export.hpp"

#include "io/cache_file.hpp"
#include "io/usd/weft_usd.hpp"
#include "weft_version.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace weft::io {

bool usd_export_built() {
#ifdef WEFT_USD_MODULE
  return true;
#else
  return false;
#endif
}

bool is_usd_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".usd" || ext == ".usda" || ext == ".usdc";
}

namespace {

#ifdef WEFT_USD_MODULE
// weft_usd.so: beside the running weft, else where the build put it. Loaded once.
usd::WriterFn load_writer() {
  static usd::WriterFn writer = nullptr;
  if (writer) return writer;
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path module = fs::read_symlink("/proc/self/exe", ec).parent_path() / fs::path(WEFT_USD_MODULE).filename();
  if (ec || !fs::exists(module, ec)) module = WEFT_USD_MODULE;
  void* handle = ::dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    throw std::runtime_error(std::string("cannot load weft's USD writer: ") + ::dlerror() +
                             " (are the OpenUSD wheels it was built with still installed? scripts/setup.sh, "
                             "then rebuild)");
  writer = reinterpret_cast<usd::WriterFn>(::dlsym(handle, usd::kWriterSymbol));
  if (!writer) throw std::runtime_error(module.string() + " has no " + usd::kWriterSymbol + ": rebuild weft");
  return writer;
}
#endif

}  // namespace

void write_usd_cache(const std::string& path, const CacheReader& cache, int first, int last) {
#ifndef WEFT_USD_MODULE
  (void)path, (void)cache, (void)first, (void)last;
  throw std::runtime_error(kNoUsdExport);
#else
  if (!is_usd_path(path)) throw std::runtime_error(path + ": a USD file ends in .usd, .usda or .usdc");
  const std::vector<int>& stored = cache.frames();
  if (stored.empty() || first > last || first < stored.front() || last > stored.back())
    throw std::runtime_error(cache.path() + ": no frames " + std::to_string(first) + "-" + std::to_string(last));
  const usd::WriterFn writer = load_writer();

  usd::MeshCache mesh;
  mesh.generator = std::string("weft ") + WEFT_VERSION;
  mesh.scene = cache.header().scene;
  mesh.source = std::filesystem::absolute(cache.path()).lexically_normal().string();
  mesh.fps = static_cast<double>(cache.header().settings.fps);
  for (int f = first; f <= last; ++f) mesh.frames.push_back(f);
  mesh.points = cache.header().points;
  mesh.triangles = cache.header().triangles;
  mesh.frame = [&](size_t k, std::vector<float>& x, std::vector<float>& v) {
    const int stored_index = mesh.frames[k] - stored.front();  // stored frames are consecutive from the first
    const std::vector<Vec3> p = cache.positions(stored_index), u = cache.velocities(stored_index);
    x.resize(3 * p.size());
    v.resize(3 * u.size());
    for (size_t i = 0; i < p.size(); ++i)
      for (int c = 0; c < 3; ++c) x[3 * i + c] = static_cast<float>(p[i][c]);
    for (size_t i = 0; i < u.size(); ++i)
      for (int c = 0; c < 3; ++c) v[3 * i + c] = static_cast<float>(u[i][c]);
  };

  // The temporary keeps the extension, which tells OpenUSD the format: out.usd -> out.tmp<pid>.usd.
  namespace fs = std::filesystem;
  const fs::path final_path(path);
  fs::path tmp = final_path;
  tmp.replace_extension(".tmp" + std::to_string(::getpid()) + final_path.extension().string());
  std::string error;
  try {
    error = writer(mesh, tmp.string());
  } catch (const std::exception& e) {  // from mesh.frame: reading the cache
    error = e.what();
  }
  std::error_code ec;
  if (error.empty() && !fs::exists(tmp, ec)) error = "OpenUSD wrote no file";
  if (!error.empty()) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path + ": " + error);
  }
  fs::rename(tmp, final_path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
#endif
}

}  // namespace weft::io
