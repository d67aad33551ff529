// Test main: `--threads=N` sets the Kokkos host thread count, then every test runs.
#include "core/kokkos_compat.hpp"
#include "tests/backend_fixture.hpp"

#include <filesystem>

namespace weft::test {
std::string shared_dir() {
  std::filesystem::path p(WEFT_SHARED_DIR);
  return std::filesystem::is_directory(p) ? p.string() : std::string();
}
}  // namespace weft::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  int threads = 0;
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], "--threads=", 10) == 0) threads = std::atoi(argv[i] + 10);
  weft::compat::initialize(threads, -1);
  const int r = RUN_ALL_TESTS();
  Kokkos::finalize();
  return r;
}
