// weft::Runtime inside an application that runs Kokkos itself (this test program initialised it in main):
// the runtime uses that Kokkos and leaves it initialised.
#include "backends/backend.hpp"

namespace {

TEST(WEFT_TEST_SUITE, runtime_keeps_the_application_kokkos) {
  using Exec = WEFT_TEST_EXECSPACE;
  ASSERT_TRUE(Kokkos::is_initialized());
  {
    weft::Runtime rt(1);
    EXPECT_FALSE(rt.owns_kokkos());
  }
  ASSERT_TRUE(Kokkos::is_initialized());
  Kokkos::View<long*, Exec::memory_space> out("out", 8);
  Kokkos::parallel_for(Kokkos::RangePolicy<Exec>(0, 8), KOKKOS_LAMBDA(int i) { out(i) = i; });
  EXPECT_EQ(weft::test::to_host(out)[7], 7);
}

}  // namespace
