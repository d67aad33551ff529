// Mesh topology and scene validation.
#include "core/error.hpp"
#include "core/topology.hpp"
#include "tests/solver_scene_fixture.hpp"

namespace {

TEST(WEFT_TEST_SUITE, grid_topology_counts) {
  const int n = 5;
  const auto g = weft::io::grid(n, n, {0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  const weft::Topology t = weft::build_topology(g.tris);
  const size_t edges = 2 * n * (n + 1) + n * n;  // rows + columns + one diagonal per quad
  EXPECT_EQ(t.edges.size(), edges);
  EXPECT_EQ(t.boundary_edges.size(), size_t(4 * n));
  EXPECT_EQ(t.bend_quads.size(), edges - 4 * n);
  EXPECT_TRUE(t.nonmanifold_edges.empty());
  for (const auto& q : t.bend_quads) {  // o0, e0, e1 is a triangle's winding
    bool found = false;
    for (const auto& tri : g.tris)
      for (int k = 0; k < 3; ++k)
        found |= tri[k] == q[0] && tri[(k + 1) % 3] == q[2] && tri[(k + 2) % 3] == q[3];
    EXPECT_TRUE(found);
  }
  const auto m = weft::lumped_masses(g.x, g.tris, 2.0);
  double total = 0;
  for (double v : m) total += v;
  EXPECT_NEAR(total, 2.0 * 1.0, 1e-12);
}

void expect_rejected(const weft::Scene& s, const std::string& needle) {
  try {
    weft::validate_scene(s);
    ADD_FAILURE() << "accepted a scene that should fail with '" << needle << "'";
  } catch (const weft::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test-sheet"), std::string::npos) << e.what();
  }
}

TEST(WEFT_TEST_SUITE, invalid_scenes_are_rejected_naming_the_element) {
  const weft::Scene good = weft::test::sheet_scene(3);
  EXPECT_NO_THROW(weft::validate_scene(good));
  weft::Scene s = good;
  s.triangles[4][1] = 99;
  expect_rejected(s, "triangle 4 refers to point 99");
  s = good;
  s.points.position[5].y = std::nan("");
  expect_rejected(s, "point 5 has a non-finite position");
  s = good;
  s.points.position[s.triangles[2][1]] = s.points.position[s.triangles[2][0]];
  expect_rejected(s, "zero area");
  s = good;
  s.constraints.distance[3].b = -1;
  expect_rejected(s, "distance constraint 3");
  s = good;
  s.points.mass[2] = -1;
  expect_rejected(s, "point 2 has an invalid mass");
}

// Across each triangle's edge k (corner k to k + 1): the lowest other triangle, -1 on a boundary; three
// triangles on one edge each see the lowest other one.
TEST(WEFT_TEST_SUITE, triangle_neighbours_across_each_edge) {
  const std::vector<std::array<int, 3>> t = {{0, 1, 2}, {2, 1, 3}, {1, 0, 4}, {0, 1, 5}};
  const auto nb = weft::triangle_neighbours(t);
  ASSERT_EQ(nb.size(), 4u);
  EXPECT_EQ(nb[0], (std::array<int, 3>{2, 1, -1}));  // edge 0-1 also in 2 and 3: the lowest, 2
  EXPECT_EQ(nb[1], (std::array<int, 3>{0, -1, -1}));
  EXPECT_EQ(nb[2], (std::array<int, 3>{0, -1, -1}));
  EXPECT_EQ(nb[3], (std::array<int, 3>{0, -1, -1}));
  const weft::Topology topo = weft::build_topology(t);
  EXPECT_EQ(topo.edges[size_t(topo.edge_index(1, 0))], (std::array<int, 2>{0, 1}));
  EXPECT_EQ(topo.edge_index(3, 4), -1);
}

}  // namespace
