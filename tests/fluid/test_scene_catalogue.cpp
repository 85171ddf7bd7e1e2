// Every shipped scene with a fluid section parses and sets up (the catalogue cannot rot silently).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "fluid_solver/core/simulation.h"
#include "fluid_solver/io/fluid_output.h"

namespace cosim::fluid::test {
namespace {

TEST(SceneCatalogue, FluidScenesParseAndSetUp) {
  int count = 0;
  for (const char* dir : {"configs", "bench/fluid"})
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(COSIM_SOURCE_DIR) / dir)) {
      if (e.path().extension() != ".yaml") continue;
      std::ifstream in(e.path());
      std::stringstream ss;
      ss << in.rdbuf();
      if (ss.str().find("\nfluid:") == std::string::npos) continue;
      FluidScene s;
      ASSERT_NO_THROW(s = load_fluid_scene(e.path().string())) << e.path();
      if (s.cells[0] * s.cells[1] * s.cells[2] <= 300000) {
        std::unique_ptr<FluidSimulation> sim;
        EXPECT_NO_THROW(sim = make_simulation(s)) << e.path();
        // cosim check's snapshot size counts the fields a snapshot has (a coupled run's embedded categories
        // come with the coupler's first faces)
        if (sim && !s.coupled) {
          EXPECT_EQ(snapshot_values_per_cell(s), SnapshotFields(*sim).values_per_cell()) << e.path();
        }
      }
      ++count;
    }
  EXPECT_GE(count, 6);
}

}  // namespace
}  // namespace cosim::fluid::test
