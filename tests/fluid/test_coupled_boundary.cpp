// The fluid side of a coupled cycle without a coupler: the solid's faces (coupling::Faces) as an embedded
// surface, the samples next to them, and the interface velocity reaching the ghost records.
#include <gtest/gtest.h>

#include <cmath>

#include "fluid_solver/core/scene.h"
#include "fluid_solver/coupled/coupled_boundary.h"
#include "fluid_solver/interface/interface_surface.h"

using namespace cosim;
using namespace cosim::fluid;

namespace {

// The boundary of the box [x0, x1] x [y0, y1] as a solid would send it: 4 segments, outward normals, the
// vertex order of each segment deliberately mixed (the fluid orients by the normals).
coupling::Faces box_faces_2d(double x0, double x1, double y0, double y1, double vx, double vy) {
  coupling::Faces f;
  f.dim = 2;
  f.count = 4;
  f.nodes_per_face = 2;
  f.vertex_position = {x0, y0, x1, y0, x1, y1, x0, y1};
  f.face_vertex = {0, 1, 2, 1, 2, 3, 0, 3};  // bottom, right, top, left
  f.normal = {0, -1, 1, 0, 0, 1, -1, 0};
  f.centre = {0.5 * (x0 + x1), y0, x1, 0.5 * (y0 + y1), 0.5 * (x0 + x1), y1, x0, 0.5 * (y0 + y1)};
  f.area = {x1 - x0, y1 - y0, x1 - x0, y1 - y0};
  f.velocity = {vx, vy, vx, vy, vx, vy, vx, vy};
  f.normal_stress.assign(4, 0.0);
  f.impedance.assign(4, INFINITY);
  return f;
}

FluidScene channel_scene() {
  return parse_fluid_scene(R"(
fluid:
  mesh: {cells: [20, 10], lower: [0.0, 0.0], upper: [2.0, 1.0]}
  phases: [{name: gas, eos: {type: ideal_gas, gamma: 1.4}}]
  time: {end: 1.0}
  boundaries: {x_lower: wall, x_upper: wall, y_lower: wall, y_upper: wall}
  initial:
    state: {rho: 1.2, velocity: [3.0, 0.0], p: 1.0e5}
)");
}

}  // namespace

TEST(CoupledBoundary, FacesBecomeAnOrientedSurfacePlacedAtTheStartOfTheStep) {
  const auto f = box_faces_2d(0.5, 1.0, 0.25, 0.75, 2.0, -1.0);
  const auto s = interface::surface_from_faces(f, 2, 0.1);
  ASSERT_EQ(s.surface.faces.size(), 4u);
  ASSERT_EQ(s.source_face, (std::vector<int>{0, 1, 2, 3}));
  for (int i = 0; i < 4; ++i) {
    const auto n = fluid::embedded::face_normal(s.surface, i);
    EXPECT_NEAR(n[0], f.normal[2 * i], 1e-14) << i;
    EXPECT_NEAR(n[1], f.normal[2 * i + 1], 1e-14) << i;
  }
  // Rigid motion: every vertex has the face velocity, and sits dt * v behind the position sent.
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(s.surface.velocities[v][0], 2.0, 1e-14);
    EXPECT_NEAR(s.surface.velocities[v][1], -1.0, 1e-14);
    EXPECT_NEAR(s.surface.vertices[v][0], f.vertex_position[2 * v] - 0.2, 1e-14);
    EXPECT_NEAR(s.surface.vertices[v][1], f.vertex_position[2 * v + 1] + 0.1, 1e-14);
  }
}

TEST(CoupledBoundary, QuadsBecomeTwoTrianglesWithTheFaceNormal) {
  // The +x face of a unit cube, vertices listed clockwise seen from outside (the fluid must flip them).
  coupling::Faces f;
  f.dim = 3;
  f.count = 1;
  f.nodes_per_face = 4;
  f.vertex_position = {1, 0, 0, 1, 0, 1, 1, 1, 1, 1, 1, 0};
  f.face_vertex = {0, 1, 2, 3};
  f.normal = {1, 0, 0};
  f.centre = {1, 0.5, 0.5};
  f.area = {1};
  f.velocity = {0, 0, 0};
  f.normal_stress = {0};
  f.impedance = {1e6};
  const auto s = interface::surface_from_faces(f, 3, 0.0);
  ASSERT_EQ(s.surface.faces.size(), 2u);
  EXPECT_EQ(s.source_face, (std::vector<int>{0, 0}));
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(fluid::embedded::face_normal(s.surface, i)[0], 1.0, 1e-14);
}

TEST(CoupledBoundary, MalformedFacesAreRefusedWithTheField) {
  auto f = box_faces_2d(0.5, 1.0, 0.25, 0.75, 0, 0);
  f.face_vertex[3] = 17;
  try {
    interface::surface_from_faces(f, 2, 0.0);
    FAIL() << "accepted a vertex index out of range";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("face_vertex[3] = 17"), std::string::npos) << e.what();
  }
  f = box_faces_2d(0.5, 1.0, 0.25, 0.75, 0, 0);
  EXPECT_THROW(interface::surface_from_faces(f, 3, 0.0), std::invalid_argument);  // 2D faces, 3D grid
  f.area.pop_back();
  EXPECT_THROW(interface::surface_from_faces(f, 2, 0.0), std::invalid_argument);
}

TEST(CoupledBoundary, SamplesReadTheFluidNextToEachFaceAndTheWallTakesUI) {
  FluidScene scene = channel_scene();
  auto sim = make_simulation(scene);
  auto cb = coupled::make_coupled_boundary(*sim);
  // A box that reaches below the channel: its bottom face lies outside the fluid and is not wetted.
  const auto f = box_faces_2d(0.8, 1.2, -0.2, 0.6, 0.0, 0.0);
  const coupling::FluidSamples s = cb->receive_faces(f, 0.0);
  ASSERT_EQ(s.count, 4);
  ASSERT_EQ(s.phases, 1);
  EXPECT_EQ(s.wetted, (std::vector<char>{0, 1, 1, 1}));
  for (int i = 1; i < 4; ++i) {
    EXPECT_NEAR(s.rho[i], 1.2, 1e-12) << i;
    EXPECT_NEAR(s.pressure[i], 1e5, 1e-6) << i;
    EXPECT_NEAR(s.alpha[i], 1.0, 1e-14) << i;
    EXPECT_NEAR(s.normal_velocity[i], 3.0 * f.normal[2 * i], 1e-12) << i;  // u . n with u = (3, 0)
    EXPECT_NEAR(s.impedance[i], 1.2 * std::sqrt(1.4 * 1e5 / 1.2), 1e-6) << i;
  }
  // The coupler's u_I per face becomes the normal wall velocity of the ghosts next to that face.
  coupling::InterfaceStates st;
  st.count = 4;
  st.phases = 1;
  st.pressure.assign(4, 1e5);
  st.normal_velocity = {0.0, 5.0, -7.0, 11.0};  // bottom, right, top, left
  cb->apply_states(st);
  const EmbeddedState& e = sim->embedded();
  ASSERT_TRUE(e.active);
  int right = 0, left = 0, top = 0;
  for (const GhostRecord& g : e.ghosts) {
    double un = 0;
    for (int d = 0; d < 3; ++d) un += g.wall_velocity[d] * g.normal[d];
    if (g.normal[0] > 0.99) {
      EXPECT_NEAR(un, 5.0, 1e-12);
      ++right;
    } else if (g.normal[0] < -0.99) {
      EXPECT_NEAR(un, 11.0, 1e-12);
      ++left;
    } else if (g.normal[1] > 0.99) {
      EXPECT_NEAR(un, -7.0, 1e-12);
      ++top;
    }
  }
  EXPECT_GT(right, 0);
  EXPECT_GT(left, 0);
  EXPECT_GT(top, 0);
  // Wrong counts are refused.
  st.count = 3;
  EXPECT_THROW(cb->apply_states(st), std::invalid_argument);
}
