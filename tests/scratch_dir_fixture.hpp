// A scratch folder per test under the system's temporary folder, removed at the end. The process id in its
// name keeps apart the runs ctest -j starts at once (the same test at 1 and 2 threads, or on two backends).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace weft::test {

struct ScratchDir {
  std::filesystem::path path;
  explicit ScratchDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("weft_test_" + std::to_string(::getpid()) + "_" + name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() { std::filesystem::remove_all(path); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string file(const std::string& name) const { return (path / name).string(); }
  // Writes `bytes` to `name` (its folders made as needed); returns the file's path.
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::filesystem::path p = path / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
  std::string read(const std::string& name) const {
    std::ifstream in(file(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // The names in the folder `sub` ("": the scratch folder itself), sorted; none when it does not exist.
  std::set<std::string> entries(const std::string& sub = "") const {
    std::set<std::string> names;
    if (std::filesystem::is_directory(path / sub))
      for (const auto& e : std::filesystem::directory_iterator(path / sub)) names.insert(e.path().filename().string());
    return names;
  }
};

}  // namespace weft::test
