// What docs/protocol.md promises an outside solver author when something is wrong: a Heartbeat sent on the data
// connection is named once in the coupler's log (and in the verdict when that peer is declared dead), a wrong
// token's refusal says where the token comes from, and a summary.json without its energy block still gives an
// energy account (the solver's part null, a one-line notice).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <thread>

#include "common/coupling/scene_hash.h"
#include "common/coupling/wire.h"
#include "common/coupling/zmq_socket.h"
#include "coupling_test_util.h"
#include "launcher/energy_account.h"

using namespace cosim;
using namespace cosim::test;
using launcher::Child;
namespace pb = coupling::pb;

namespace {
const char* kRun = "  time: {end: 1.0e-3}\n  output: {interval: 5.0e-4}\n  timeout: 2.0\n  connect_timeout: 5\n";

// A solid's Hello, sent by the test itself on a raw DEALER connection.
std::string hello(const std::string& token, const std::string& scene_hash) {
  pb::Envelope e = coupling::make_envelope(coupling::Role::Solid, token, -1, 0.0);
  e.mutable_hello()->set_role(pb::ROLE_SOLID);
  e.mutable_hello()->set_scene_hash(scene_hash);
  e.mutable_hello()->set_program("raw_solid");
  return coupling::encode(e);
}

pb::Welcome welcome(coupling::ZmqSocket& s) {
  coupling::Frames f;
  EXPECT_TRUE(s.receive(f, 5000)) << "no Welcome";
  std::string why;
  const auto e = f.empty() ? std::nullopt : coupling::decode(f[0], why);
  EXPECT_TRUE(e && e->has_welcome()) << why;
  return e ? e->welcome() : pb::Welcome();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST(ProtocolContract, WrongTokenRefusalSaysWhereTheTokenComesFrom) {
  const fs::path dir = test_dir("contract_token");
  const fs::path scene = write_scene(dir, kRun);
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  std::vector<Child> cs{child("coupler", coupler_args(ep, scene, dir / "out"), dir)};
  launcher::start(cs[0]);
  coupling::ZmqContext ctx;
  coupling::ZmqSocket s(ctx, coupling::ZmqSocket::Type::Dealer);
  s.connect(ep);
  ASSERT_TRUE(s.send({hello("forged", coupling::scene_hash(scene.string(), {}))}));
  const pb::Welcome w = welcome(s);
  EXPECT_FALSE(w.accepted());
  EXPECT_NE(w.reason().find("wrong run token"), std::string::npos) << w.reason();
  EXPECT_NE(w.reason().find("$COSIM_TOKEN"), std::string::npos) << w.reason();
  launcher::stop(cs[0], 0.5);
}

// A solid that beats on the data connection: the coupler names it once, with where heartbeats go, and when the
// solid then owes its faces past the timeout the verdict says why it was not seen alive.
TEST(ProtocolContract, HeartbeatOnTheDataConnectionIsNamedOnce) {
  const fs::path dir = test_dir("contract_heartbeat");
  const fs::path scene = write_scene(dir, kRun);
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  std::vector<Child> cs{child("coupler", coupler_args(ep, scene, dir / "out"), dir),
                        child("fluid", peer_args("fluid", ep, scene), dir)};
  for (auto& c : cs) launcher::start(c);
  coupling::ZmqContext ctx;
  coupling::ZmqSocket s(ctx, coupling::ZmqSocket::Type::Dealer);
  s.connect(ep);
  ASSERT_TRUE(s.send({hello("tok", coupling::scene_hash(scene.string(), {}))}));
  const pb::Welcome w = welcome(s);
  ASSERT_TRUE(w.accepted()) << w.reason();
  pb::Envelope beat = coupling::make_envelope(coupling::Role::Solid, "tok", 0, 0.0);
  beat.mutable_heartbeat();
  for (int k = 0; k < 40; ++k) {  // 4 s of beats on the wrong connection; the coupler's timeout is 2 s
    s.send({coupling::encode(beat)}, 100);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::vector<Child> coupler{cs[0]}, fluid{cs[1]};
  wait_all(coupler, 10);
  wait_all(fluid, 5);
  const std::string log = read_file(cs[0].log);
  EXPECT_EQ(coupler[0].exit_code, 5) << log;
  EXPECT_EQ(count(log, "sent a Heartbeat on the data connection"), 1u) << log;
  EXPECT_NE(log.find("solid (raw_solid, pid 0) sent a Heartbeat on the data connection, where heartbeats are ignored: "
                     "they go to the heartbeat connection, Welcome.heartbeat_endpoint = " +
                     w.heartbeat_endpoint()),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("declared dead: no message or heartbeat for"), std::string::npos) << log;
  EXPECT_NE(log.find("it sent its heartbeats on the data connection, not to Welcome.heartbeat_endpoint"),
            std::string::npos)
      << log;
}

// summary.json's energy block is optional (docs/protocol.md, "summary.json"): without it the account holds the
// fluid's part, the solid's null with the reason, and no totals; with both parts the totals are there.
TEST(ProtocolContract, EnergyAccountWithoutTheSolidsEnergyBlock) {
  const fs::path dir = test_dir("contract_energy");
  fs::create_directories(dir / "fluid");
  fs::create_directories(dir / "solid");
  std::ofstream(dir / "fluid" / "summary.json")
      << R"({"totals": {"start": [{"phase": "gas", "energy": 10.0}], "end": [{"phase": "gas", "energy": 12.5}]}})";
  std::ofstream(dir / "solid" / "summary.json") << R"({"status": "completed"})";
  EXPECT_EQ(launcher::write_energy_account(dir), "");
  ASSERT_TRUE(fs::exists(dir / "energy_account.json"));
  nlohmann::json a = nlohmann::json::parse(read_file(dir / "energy_account.json"));
  EXPECT_DOUBLE_EQ(a["fluid"]["change"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(a["fluid"]["boundary_inflow"].get<double>(), 0.0);
  EXPECT_TRUE(a["solid"].is_null());
  EXPECT_FALSE(a.contains("total_change"));
  EXPECT_EQ(a["missing"], "solid/summary.json has no \"energy\" block");

  fs::remove(dir / "solid" / "summary.json");  // no summary at all (a solver that writes none)
  EXPECT_EQ(launcher::write_energy_account(dir), "");
  a = nlohmann::json::parse(read_file(dir / "energy_account.json"));
  EXPECT_EQ(a["missing"], "solid/summary.json is missing");

  std::ofstream(dir / "solid" / "summary.json") << R"({"energy": {"start": {"total": 5.0}, "end": {"total": 4.0}}})";
  EXPECT_EQ(launcher::write_energy_account(dir), "");
  a = nlohmann::json::parse(read_file(dir / "energy_account.json"));
  EXPECT_DOUBLE_EQ(a["total_change"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(a["solid"]["boundary_work"].get<double>(), 0.0);
  EXPECT_FALSE(a.contains("missing"));
}
