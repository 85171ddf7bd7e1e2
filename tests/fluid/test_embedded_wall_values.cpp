// A coupled conservative cycle builds the embedded state once (receive_faces) and then sets only the records' wall
// velocities and pressures in place from the interface states (set_wall_values over EmbeddedState::wall_sources,
// FluidSimulation::set_embedded_walls): each record must then hold the same values, bit for bit, as in the state
// built with those states from the start (to_embedded_state with the wall speeds and pressures).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "fluid_solver/core/embedded_bodies.h"
#include "fluid_solver/embedded/shapes.h"

using namespace cosim::fluid;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <std::size_t N>
bool same_bits(const std::array<double, N>& a, const std::array<double, N>& b) {
  for (std::size_t i = 0; i < N; ++i)
    if (!same_bits(a[i], b[i])) return false;
  return true;
}

void expect_same_walls(const GhostRecord& a, const GhostRecord& b, const std::string& what) {
  EXPECT_EQ(a.cell, b.cell) << what;
  EXPECT_TRUE(same_bits(a.wall_velocity, b.wall_velocity)) << what << " cell " << a.cell;
  EXPECT_EQ(a.has_wall_pressure, b.has_wall_pressure) << what << " cell " << a.cell;
  if (!a.has_wall_pressure) return;
  EXPECT_TRUE(same_bits(a.wall_pressure, b.wall_pressure)) << what << " cell " << a.cell;
}

void expect_same_walls(const WallFace& a, const WallFace& b, const std::string& what) {
  EXPECT_EQ(a.fluid_cell, b.fluid_cell) << what;
  EXPECT_EQ(a.solid_cell, b.solid_cell) << what;
  EXPECT_TRUE(same_bits(a.wall_velocity, b.wall_velocity)) << what << " face " << a.fluid_cell << "-" << a.solid_cell;
}

// Per surface face: a normal interface speed unlike the surface's, and a wall pressure (NaN on every third face:
// no pressure there).
void interface_states(const embedded::Surface& s, std::vector<double>& speed, std::vector<double>& pressure) {
  speed.clear();
  pressure.clear();
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    speed.push_back(0.7 - 0.13 * static_cast<double>(f % 7));
    pressure.push_back(f % 3 == 2 ? NAN : 1e5 + 321.5 * static_cast<double>(f));
    pressure.push_back(2e5 - 17.25 * static_cast<double>(f));
  }
}

// The state built without the interface states, its walls then set in place, against the state built with them.
template <int DIM>
void expect_in_place_walls_equal_a_new_state(const Grid<DIM>& g, const embedded::Surface& s, const std::string& what,
                                             std::size_t& records, std::size_t& side_records) {
  const auto geo = embedded::build_geometry<DIM>(g, s, embedded::GeometryOptions{});
  std::vector<double> speed, pressure;
  interface_states(s, speed, pressure);
  const EmbeddedState fresh = to_embedded_state<DIM>(g, s, geo, &speed, &pressure);
  EmbeddedState in_place = to_embedded_state<DIM>(g, s, geo);
  set_wall_values(in_place, wall_values(in_place.wall_sources, &speed, &pressure));

  ASSERT_EQ(fresh.ghosts.size(), in_place.ghosts.size()) << what;
  ASSERT_FALSE(fresh.ghosts.empty()) << what;
  for (std::size_t i = 0; i < fresh.ghosts.size(); ++i) expect_same_walls(fresh.ghosts[i], in_place.ghosts[i], what);
  records += fresh.ghosts.size();
  for (int D = 0; D < DIM; ++D) {
    ASSERT_EQ(fresh.faces[D].size(), in_place.faces[D].size()) << what;
    for (std::size_t i = 0; i < fresh.faces[D].size(); ++i)
      expect_same_walls(fresh.faces[D][i], in_place.faces[D][i], what + " wall face");
    ASSERT_EQ(fresh.side_ghosts[D].size(), in_place.side_ghosts[D].size()) << what;
    for (std::size_t i = 0; i < fresh.side_ghosts[D].size(); ++i)
      expect_same_walls(fresh.side_ghosts[D][i].ghost, in_place.side_ghosts[D][i].ghost, what + " side ghost");
    ASSERT_EQ(fresh.blocked[D].size(), in_place.blocked[D].size()) << what;
    for (std::size_t i = 0; i < fresh.blocked[D].size(); ++i) {
      expect_same_walls(fresh.blocked[D][i].low, in_place.blocked[D][i].low, what + " blocked face");
      expect_same_walls(fresh.blocked[D][i].high, in_place.blocked[D][i].high, what + " blocked face");
    }
    records += fresh.faces[D].size() + fresh.side_ghosts[D].size() + 2 * fresh.blocked[D].size();
    side_records += fresh.side_ghosts[D].size() + 2 * fresh.blocked[D].size();
  }
  // The interface states reached the records: the in-place values are not the surface's.
  bool changed = false;
  const EmbeddedState plain = to_embedded_state<DIM>(g, s, geo);
  for (std::size_t i = 0; i < plain.ghosts.size(); ++i)
    changed = changed || !same_bits(plain.ghosts[i].wall_velocity, in_place.ghosts[i].wall_velocity);
  EXPECT_TRUE(changed) << what;
}

}  // namespace

TEST(EmbeddedWallValues, InPlaceWallsEqualTheStateBuiltWithThem) {
  std::size_t records = 0, side_records = 0;
  const Grid<2> g({64, 64, 1}, {0, 0, 0}, {1, 1, 1});
  // A moving box turned by 20 degrees (wall faces that take the flow cell's wall, corners), a moving circle, and a
  // plate thinner than a cell (side ghosts and blocked faces).
  expect_in_place_walls_equal_a_new_state<2>(
      g, embedded::make_box(2, {0.3, 0.35, 0}, {0.62, 0.6, 0}, {0.4, -0.25, 0}, 20.0), "turned box", records,
      side_records);
  expect_in_place_walls_equal_a_new_state<2>(g, embedded::make_circle({0.503, 0.497, 0}, 0.2, 48, {-0.3, 0.1, 0}),
                                             "circle", records, side_records);
  EXPECT_EQ(side_records, 0u);
  expect_in_place_walls_equal_a_new_state<2>(
      g, embedded::make_box(2, {0.3, 0.503, 0}, {0.7, 0.503 + 0.4 / 64, 0}, {0.0, 0.5, 0}), "thin plate", records,
      side_records);
  EXPECT_GT(side_records, 0u);  // the plate's side ghosts and blocked faces were compared
  const Grid<3> g3({24, 24, 24}, {0, 0, 0}, {1, 1, 1});
  expect_in_place_walls_equal_a_new_state<3>(
      g3, embedded::make_box(3, {0.3, 0.3, 0.3}, {0.7, 0.6, 0.65}, {0.2, 0.1, -0.3}, 30.0), "turned 3D box", records,
      side_records);
  std::printf(
      "[ measured ] %zu records (%zu of thin bodies) set in place, the same bits as built with the "
      "interface states\n",
      records, side_records);
}
