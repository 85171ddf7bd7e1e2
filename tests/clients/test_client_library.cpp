// libcosim_client without a coupler: settings, the scene queries, the scene hash the solvers compute, and the
// status codes and messages of calls that cannot succeed (through the C++ interface over the C one).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/checkpoint/checkpoint_sets.h"
#include "common/util/sha256.h"
#include "cosim/client.hpp"
#include "tests/support/scratch_dir.h"

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

// The protocol this library speaks, and the MPI ranks a solver's Hello may claim (1 to 1000000; the coupler refuses
// more): a wrong count is refused before any connection, naming the value.
TEST(ClientLibrary, SpeaksVersion7AndChecksTheRanksOfItsHello) {
  EXPECT_EQ(cosim_protocol_version(), 7);
  cosim::client::Client c(cosim::client::Role::Fluid);
  c.set_ranks(1);
  c.set_ranks(1000000);
  for (const int bad : {0, -2, 1000001}) {
    try {
      c.set_ranks(bad);
      FAIL() << "ranks " << bad << " accepted";
    } catch (const cosim::client::Error& e) {
      EXPECT_EQ(e.code(), COSIM_E_ARGUMENT);
      EXPECT_NE(std::string(e.what()).find("cosim_set_ranks: " + std::to_string(bad) + ", expected 1 to 1000000"),
                std::string::npos)
          << e.what();
    }
  }
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

// A checkpoint part as an outside solver reads it back (cosim_client_verify_part, cosim_read_part): the manifest's
// size and SHA-256 of the part, the set's cycle and time; a flipped bit, a truncated part, a manifest moved to the
// set of another cycle and a part the manifest does not list are refused, naming the file and what differs.
TEST(ClientLibrary, ACheckpointPartIsReadOnlyWhenItMatchesItsManifest) {
  namespace fs = std::filesystem;
  const fs::path root = cosim::test::scratch_path("client_part_sets");
  fs::remove_all(root);
  const fs::path set = cosim::checkpoint::set_path(root, 42);
  fs::create_directories(set);
  const std::vector<double> state = {1.0, 42.0, 0.5, -1.25e-3, 3.0, 0.1, 7.0};
  {
    std::ofstream out(set / "solid.bin", std::ios::binary);
    out.write(reinterpret_cast<const char*>(state.data()), static_cast<std::streamsize>(state.size() * 8));
  }
  cosim::checkpoint::write_manifest(set, 42, 0.5, {{"parts", {"solid.bin"}}});
  const std::string expected_sha = cosim::util::sha256_of_file(set / "solid.bin").sha256;

  const cosim::client::PartRecord r = cosim::client::verify_part(set.string(), "solid.bin");
  EXPECT_EQ(r.bytes, 56);
  EXPECT_EQ(r.sha256, expected_sha);
  EXPECT_EQ(r.cycle, 42);
  EXPECT_EQ(r.time, 0.5);
  const std::vector<unsigned char> bytes = cosim::client::read_part(set.string(), "solid.bin");
  ASSERT_EQ(bytes.size(), 56u);
  EXPECT_EQ(std::memcmp(bytes.data(), state.data(), 56), 0);
  // Too small a buffer: refused, the length said.
  double small[2];
  long long length = 0;
  EXPECT_EQ(cosim_read_part(set.c_str(), "solid.bin", small, sizeof small, &length), COSIM_E_ARGUMENT);
  EXPECT_EQ(length, 56);

  const auto refused = [&](const fs::path& dir, const std::string& part, const std::string& what) {
    long long n = 0;
    double buffer[16];
    EXPECT_EQ(cosim_read_part(dir.c_str(), part.c_str(), buffer, sizeof buffer, &n), COSIM_E_CORRUPT) << what;
    const std::string message = cosim_last_error();
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(cosim_client_verify_part(dir.c_str(), part.c_str(), nullptr, nullptr, nullptr, nullptr), COSIM_E_CORRUPT);
  };
  refused(set, "fluid.bin", "lists no part fluid.bin");
  {  // one bit of the fourth double flipped
    std::fstream f(set / "solid.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(3 * 8 + 2);
    f.put(static_cast<char>(reinterpret_cast<const unsigned char*>(&state[3])[2] ^ 0x10));
  }
  refused(set, "solid.bin", (set / "solid.bin").string() + ": SHA-256 ");
  refused(set, "solid.bin", "the manifest recorded " + expected_sha + ": the part is corrupt");
  fs::resize_file(set / "solid.bin", 48);
  refused(set, "solid.bin", (set / "solid.bin").string() + ": 48 bytes, the manifest recorded 56");
  const fs::path moved = cosim::checkpoint::set_path(root, 43);
  fs::rename(set, moved);
  refused(moved, "solid.bin", "says cycle 42, but the set is that of cycle 000000043");
}
