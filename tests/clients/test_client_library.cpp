// libcosim_client without a coupler: settings, the scene queries, the scene hash the solvers compute, and the
// status codes and messages of calls that cannot succeed (through the C++ interface over the C one).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "cosim/client.hpp"

namespace {

const std::string scene = std::string(COSIM_SOURCE_DIR) + "/configs/piston_2d.yaml";

TEST(ClientLibrary, ReadsTheSceneWithItsOverrides) {
  cosim::client::Client c(cosim::client::Role::Solid);
  c.set_scene(scene);
  c.add_override("solid.blocks.0.density=250");
  EXPECT_EQ(c.scene_string("solid.blocks.0.name"), "piston");
  EXPECT_EQ(c.scene_number("solid.blocks.0.density"), 250.0);
  EXPECT_EQ(c.scene_numbers("solid.mesh.upper"), (std::vector<double>{0.0, 0.8}));
  EXPECT_EQ(c.scene_length("solid.blocks"), 1);
  EXPECT_TRUE(c.scene_has("coupling.mode"));
  EXPECT_FALSE(c.scene_has("solid.mesh.regions"));
  try {
    c.scene_number("solid.blocks.3.density");
    FAIL() << "a missing key was read";
  } catch (const cosim::client::Error& e) {
    EXPECT_EQ(e.code(), COSIM_E_NOT_FOUND);
    EXPECT_NE(std::string(e.what()).find("no entry 3"), std::string::npos) << e.what();
  }
}

TEST(ClientLibrary, SceneHashDependsOnTheOverrides) {
  char a[17], b[17];
  const char* overrides[] = {"coupling.time.end=0.01"};
  ASSERT_EQ(cosim_scene_hash(scene.c_str(), nullptr, 0, a), COSIM_OK);
  ASSERT_EQ(cosim_scene_hash(scene.c_str(), overrides, 1, b), COSIM_OK);
  EXPECT_EQ(std::string(a).size(), 16u);
  EXPECT_NE(std::string(a), std::string(b));
  EXPECT_EQ(cosim_scene_hash("/nonexistent.yaml", nullptr, 0, a), COSIM_E_SCENE);
  EXPECT_NE(std::string(cosim_last_error()).find("/nonexistent.yaml"), std::string::npos);
}

TEST(ClientLibrary, ParsesTheSolverCommandLine) {
  const char* argv[] = {"piston", "scene.yaml", "--out",     "run/solid", "--coupler", "ipc:///tmp/x.sock",
                        "--set",  "a.b=1",      "--restart", "set7"};
  cosim::client::Client c(cosim::client::Role::Solid, 10, const_cast<char**>(argv));
  EXPECT_EQ(c.scene_file(), "scene.yaml");
  EXPECT_EQ(c.out_dir(), "run/solid");
  EXPECT_EQ(c.restart_set(), "set7");
  const char* bad[] = {"piston", "scene.yaml", "--frobnicate"};
  cosim_client* h = nullptr;
  ASSERT_EQ(cosim_create(&h, COSIM_ROLE_FLUID), COSIM_OK);
  EXPECT_EQ(cosim_parse_args(h, 3, const_cast<char**>(bad)), COSIM_E_ARGUMENT);
  EXPECT_NE(std::string(cosim_last_error()).find("--frobnicate"), std::string::npos);
  cosim_close(h);
}

TEST(ClientLibrary, RefusesCallsOutOfOrder) {
  cosim_client* h = nullptr;
  EXPECT_EQ(cosim_create(&h, 7), COSIM_E_ARGUMENT);
  EXPECT_EQ(h, nullptr);
  ASSERT_EQ(cosim_create(&h, COSIM_ROLE_SOLID), COSIM_OK);
  cosim_directive d;
  EXPECT_EQ(cosim_next(h, &d), COSIM_E_ARGUMENT);
  EXPECT_NE(std::string(cosim_last_error()).find("cosim_hello"), std::string::npos);
  EXPECT_EQ(cosim_hello(h), COSIM_E_ARGUMENT);  // no endpoint
  cosim_close(h);
  cosim_close(nullptr);
}

// No coupler at the endpoint: the handshake gives up after the connect timeout with COSIM_E_PEER_LOST.
TEST(ClientLibrary, HelloWithoutACouplerTimesOut) {
  cosim::client::Client c(cosim::client::Role::Solid);
  c.set_endpoint("ipc://" + std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                 "/cosim-client-test-nobody.sock");
  c.set_scene(scene);
  c.set_connect_timeout(0.3);
  try {
    c.hello();
    FAIL() << "connected to nobody";
  } catch (const cosim::client::Error& e) { EXPECT_EQ(e.code(), COSIM_E_PEER_LOST) << e.what(); }
}

}  // namespace
