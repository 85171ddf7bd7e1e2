// Coupler + scripted peers as separate processes: handshake, refusals on both sides, malformed bytes,
// a killed peer, the protocol transcript.
#include <gtest/gtest.h>
#include <signal.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "common/coupling/wire.h"
#include "common/coupling/zmq_socket.h"
#include "coupler/stranger_limit.h"
#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;
using launcher::Child;

namespace {
const char* kShort = "  time: {end: 1.0e-3}\n  output: {interval: 5.0e-4}\n  timeout: 2.0\n  connect_timeout: 5\n";
const char* kLong = "  time: {end: 1.0e9}\n  timeout: 5.0\n";  // runs until stopped

struct ThreeProcs {
  fs::path dir, scene;
  std::string ep;
  std::vector<Child> cs;  // coupler, fluid, solid
  ThreeProcs(const std::string& name, const std::string& coupling, std::vector<std::string> fluid_extra = {},
             std::vector<std::string> solid_extra = {}, std::vector<std::string> coupler_extra = {}) {
    dir = test_dir(name);
    scene = write_scene(dir, coupling);
    ep = "ipc://" + (dir / "c.sock").string();
    cs.push_back(child("coupler", coupler_args(ep, scene, dir / "out", coupler_extra), dir));
    cs.push_back(child("fluid", peer_args("fluid", ep, scene, fluid_extra), dir));
    cs.push_back(child("solid", peer_args("solid", ep, scene, solid_extra), dir));
    for (auto& c : cs) launcher::start(c);
  }
  std::string log(int i) const { return read_file(cs[i].log); }
};

// A coupler alone, waiting for its solvers, and a stranger's connection to it (a Dealer socket).
struct CouplerAndStranger {
  fs::path dir, scene;
  std::string ep;
  std::vector<Child> cs;  // the coupler
  coupling::ZmqContext ctx;
  coupling::ZmqSocket stranger{ctx, coupling::ZmqSocket::Type::Dealer};
  CouplerAndStranger(const std::string& name, const std::string& coupling) {
    dir = test_dir(name);
    scene = write_scene(dir, coupling);
    ep = "ipc://" + (dir / "c.sock").string();
    cs.push_back(child("coupler", coupler_args(ep, scene, dir / "out"), dir));
    launcher::start(cs[0]);
    stranger.connect(ep);
  }
};

// After whatever a stranger did, the run's own solvers connect and the run completes: every process exits 0.
void expect_own_run_completes(std::vector<Child> cs, const fs::path& dir, const std::string& ep,
                              const fs::path& scene) {
  std::vector<Child> peers{child("fluid", peer_args("fluid", ep, scene), dir),
                           child("solid", peer_args("solid", ep, scene), dir)};
  for (auto& c : peers) launcher::start(c);
  cs.insert(cs.end(), peers.begin(), peers.end());
  wait_all(cs, 20);
  for (auto& c : cs) EXPECT_EQ(c.exit_code, 0) << c.name << ": " << read_file(c.log);
}
}  // namespace

TEST(CouplingProcesses, HandshakeAndShortRunComplete) {
  ThreeProcs r("ok", kShort);
  wait_all(r.cs, 20);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.cs[i].exit_code, 0) << r.cs[i].name << ":\n" << r.log(i);
  EXPECT_NE(r.log(0).find("fluid (scripted_fluid, pid"), std::string::npos);
  EXPECT_NE(r.log(1).find("stop: completed: t = 0.001 s"), std::string::npos) << r.log(1);
  const std::string hist = read_file(r.dir / "out" / "interface_history.csv");
  EXPECT_EQ(std::count(hist.begin(), hist.end(), '\n'), 1 + 11) << hist;  // header + cycles 0..10
}

// A peer of version 6 (before Hello.ranks) is refused, both versions named.
TEST(CouplingProcesses, VersionMismatchRefusedOnBothSides) {
  static_assert(cosim::coupling::kProtocolVersion > 6);
  ThreeProcs r("version", kShort, {"--protocol-version", "6"});
  wait_all(r.cs, 20);
  EXPECT_EQ(r.cs[0].exit_code, 5);
  EXPECT_EQ(r.cs[1].exit_code, 5);
  EXPECT_NE(r.cs[2].exit_code, 0);
  const std::string expected = "protocol version 6 of scripted_fluid, the coupler speaks version " +
                               std::to_string(cosim::coupling::kProtocolVersion);
  EXPECT_NE(r.log(0).find(expected), std::string::npos) << r.log(0);
  EXPECT_NE(r.log(1).find("refused fluid: " + expected), std::string::npos) << r.log(1);
  // The solid is told why when it had connected before the refusal, otherwise it gets no Welcome.
  EXPECT_TRUE(r.log(2).find("coupler stopped the run: coupler: refused scripted_fluid") != std::string::npos ||
              r.log(2).find("no Welcome from the coupler") != std::string::npos)
      << r.log(2);
}

// Hello.ranks: what the solver says it speaks for is the coupler's record (coupler_summary.json "peers", the
// handshake line); not sent (a one-rank solver of an older client) reads as 1.
TEST(CouplingProcesses, HelloRanksAreRecordedByTheCoupler) {
  ThreeProcs r("hello_ranks", kShort, {"--ranks", "4"}, {"--ranks", "0"});
  wait_all(r.cs, 20);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(r.cs[i].exit_code, 0) << r.cs[i].name << ":\n" << r.log(i);
  const nlohmann::json c = nlohmann::json::parse(read_file(r.dir / "out" / "coupler_summary.json"));
  EXPECT_EQ(c["peers"]["fluid"]["ranks"].get<int>(), 4) << c.dump();
  EXPECT_EQ(c["peers"]["fluid"]["program"].get<std::string>(), "scripted_fluid") << c.dump();
  EXPECT_EQ(c["peers"]["fluid"]["pid"].get<long>(), static_cast<long>(r.cs[1].pid)) << c.dump();
  EXPECT_EQ(c["peers"]["solid"]["ranks"].get<int>(), 1) << c.dump();
  EXPECT_NE(r.log(0).find("connected, speaking for 4 MPI rank(s)"), std::string::npos) << r.log(0);
}

// An absurd Hello.ranks is the run's own solver misconfigured: refused naming the field and the value.
TEST(CouplingProcesses, AbsurdHelloRanksAreRefusedNamingTheField) {
  ThreeProcs r("absurd_ranks", kShort, {"--ranks", "1000001"});
  wait_all(r.cs, 20);
  EXPECT_EQ(r.cs[0].exit_code, 5);
  EXPECT_EQ(r.cs[1].exit_code, 5);
  EXPECT_NE(r.cs[2].exit_code, 0);
  const std::string expected = "Hello.ranks: 1000001, expected the number of MPI ranks";
  EXPECT_NE(r.log(0).find("refused scripted_fluid (pid " + std::to_string(r.cs[1].pid) + "): " + expected),
            std::string::npos)
      << r.log(0);
  EXPECT_NE(r.log(1).find("refused fluid: " + expected), std::string::npos) << r.log(1);
}

// A Hello without the run's token is a stranger's: it is refused and told why, the coupler logs it and the run
// goes on with its own solvers. One of the run's own solvers with another scene ends the start-up.
TEST(CouplingProcesses, WrongTokenIsAStrangerRefusedAndSceneHashEndsTheStart) {
  const fs::path dir = test_dir("token");
  const fs::path scene = write_scene(dir, kShort);
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  std::vector<Child> cs{child("coupler", coupler_args(ep, scene, dir / "out"), dir),
                        child("stranger", peer_args("fluid", ep, scene, {"--token", "forged"}), dir)};
  for (auto& c : cs) launcher::start(c);
  std::vector<Child> stranger{cs[1]};
  wait_all(stranger, 10);
  EXPECT_EQ(stranger[0].exit_code, 5);
  EXPECT_NE(read_file(stranger[0].log).find("wrong run token"), std::string::npos) << read_file(stranger[0].log);
  expect_own_run_completes({cs[0]}, dir, ep, scene);
  EXPECT_NE(read_file(cs[0].log).find("or from --token when started by hand); the run goes on"), std::string::npos)
      << read_file(cs[0].log);

  ThreeProcs h("hash", kShort, {}, {"--set", "coupling.mode=standard"});
  wait_all(h.cs, 20);
  EXPECT_EQ(h.cs[0].exit_code, 5);
  EXPECT_EQ(h.cs[2].exit_code, 5);
  EXPECT_NE(h.log(2).find("refused solid: scene hash"), std::string::npos) << h.log(2);
}

TEST(CouplingProcesses, MalformedBytesGetAnErrorReplyAndNoCrash) {
  CouplerAndStranger r("malformed", kShort);
  ASSERT_TRUE(r.stranger.send({std::string("\xff\xff garbage \x01", 12)}));
  coupling::Frames f;
  ASSERT_TRUE(r.stranger.receive(f, 5000)) << "no Error reply";
  std::string why;
  auto e = coupling::decode(f.at(0), why);
  ASSERT_TRUE(e.has_value()) << why;
  ASSERT_TRUE(e->has_error());
  EXPECT_NE(e->error().reason().find("malformed message (12 bytes)"), std::string::npos) << e->error().reason();
  // A stranger's garbage does not end the run: the solvers can still connect and finish.
  expect_own_run_completes(r.cs, r.dir, r.ep, r.scene);
}

// A flood from a stranger that never reads its answers: at most StrangerLimit's rate is answered, at most its
// number of lines name a message, the rest is counted in summary lines; the run's own solvers still connect and
// finish (a flood used to cut a run from 1348 to 1.7 cycles/s and write a 2.3 MB log).
TEST(CouplingProcesses, AFloodFromAStrangerIsDroppedAndTheLogStaysBounded) {
  CouplerAndStranger r("flood", kShort);
  int sent = 0;
  for (int i = 0; i < 20000; ++i) sent += r.stranger.send({std::string("flood \x01\x02", 8)}, 10) ? 1 : 0;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  expect_own_run_completes(r.cs, r.dir, r.ep, r.scene);
  const std::string log = read_file(r.cs[0].log);
  std::size_t named = 0;
  for (std::size_t at = 0; (at = log.find("ignored a message from an unknown connection", at)) != std::string::npos;
       ++at)
    ++named;
  std::printf("flood: %d messages sent, %zu named in the log, log %zu bytes\n", sent, named, log.size());
  EXPECT_GT(sent, 1000);
  EXPECT_LE(named, static_cast<std::size_t>(coupler::StrangerLimit::kMaxLogged));
  EXPECT_NE(log.find("dropped unanswered"), std::string::npos) << log.substr(0, 2000);
  EXPECT_LT(log.size(), 100000u);
}

// A message larger than coupling.max_message_mb never reaches the coupler's memory: libzmq drops the connection
// that sends it, the sender gets no answer, and the run goes on with its own solvers.
TEST(CouplingProcesses, AnOversizedMessageDropsOnlyItsConnection) {
  CouplerAndStranger r("oversized", std::string(kShort) + "  max_message_mb: 1\n");
  ASSERT_TRUE(r.stranger.send({std::string(3u << 20, 'x')}));
  coupling::Frames f;
  EXPECT_FALSE(r.stranger.receive(f, 1000)) << "the coupler answered a 3 MB message";
  expect_own_run_completes(r.cs, r.dir, r.ep, r.scene);
}

// The coupler keeps what a solver sends ahead of the cycle (a pipelined solid's faces and proposal) in that
// solver's inbox; a message that is still out of order when its turn comes, or a flood of them, stops the run
// with a message naming the peer and the message, never a hang.
TEST(CouplingProcesses, MessagesAheadOfTheCycleAreQueuedOrRefused) {
  for (const int extra : {1, 20}) {
    // The fluid answers late, so that all of the solid's extra proposals are queued while the coupler waits for it
    // (without the delay, a quick fluid lets the coupler meet the flood one message at a time).
    const std::vector<std::string> fluid_args =
        extra == 1 ? std::vector<std::string>{} : std::vector<std::string>{"--sample-delay-ms", "500"};
    ThreeProcs r("ahead_" + std::to_string(extra), kShort, fluid_args, {"--extra-proposals", std::to_string(extra)});
    wait_all(r.cs, 20);
    EXPECT_EQ(r.cs[0].exit_code, 5) << r.log(0);
    EXPECT_NE(r.cs[1].exit_code, 0);
    EXPECT_NE(r.cs[2].exit_code, 0);
    const std::string expected = extra == 1 ? "sent DtProposal out of order: expected InterfaceFaces in cycle 1"
                                            : "sent 17 messages ahead of the cycle";
    EXPECT_NE(r.log(0).find("solid (scripted_solid, pid " + std::to_string(r.cs[2].pid) + ")"), std::string::npos)
        << r.log(0);
    EXPECT_NE(r.log(0).find(expected), std::string::npos) << r.log(0);
    EXPECT_FALSE(process_with_argument(r.dir.string()));
  }
}

// A fluid that names the lowest pressure its phases admit (an ideal gas: 0 Pa) and then samples -5e5 Pa is stopped
// on receipt, the field, face and value named; the same pressure from a fluid whose EOS admits it (a stiffened gas
// with p_inf = 6e8 Pa) runs.
TEST(CouplingProcesses, ASamplePressureBelowWhatThePhaseAdmitsIsRefused) {
  ThreeProcs bad("negative_pressure", kShort, {"--min-pressure", "0", "--pressure", "-5e5"});
  wait_all(bad.cs, 20);
  EXPECT_EQ(bad.cs[0].exit_code, 5) << bad.log(0);
  EXPECT_NE(bad.cs[1].exit_code, 0);
  EXPECT_NE(bad.log(0).find("FluidSamples.pressure[0]: -500000 Pa, below the lowest pressure phase 'phase0' admits "
                            "(0 Pa, Hello.phase_min_pressure) (face 0, phase 0)"),
            std::string::npos)
      << bad.log(0);
  ThreeProcs water("admitted_pressure", kShort, {"--min-pressure", "-6e8", "--pressure", "-5e5"});
  wait_all(water.cs, 20);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(water.cs[i].exit_code, 0) << water.cs[i].name << ":\n" << water.log(i);
}

// The coupler's heartbeats have a thread and a socket of their own: a coupler whose main thread is busy for 2.5 s
// (a large message, a checkpoint) with a 1 s timeout keeps both solvers, and the run completes. A coupler that
// beats from its main thread loses them after 1 s.
TEST(CouplingProcesses, ABusyCouplerStillHeartbeats) {
  const char* scene = "  time: {end: 1.0e-3}\n  output: {interval: 5.0e-4}\n  timeout: 1.0\n  connect_timeout: 5\n";
  ThreeProcs r("busy_coupler", scene, {}, {}, {"--stall-after-cycle", "3", "--stall-seconds", "2.5"});
  wait_all(r.cs, 30);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.cs[i].exit_code, 0) << r.cs[i].name << ":\n" << r.log(i);
  // Its heartbeat socket is a file of its own beside the data socket, removed at the end.
  EXPECT_FALSE(fs::exists(r.dir / "c-hb.sock"));
}

TEST(CouplingProcesses, KilledPeerDetectedWithin5sAndEveryoneStops) {
  ThreeProcs r("killed", kLong);
  // Let the run go for a while, then kill the fluid without warning.
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  ASSERT_TRUE(r.cs[0].running && r.cs[1].running && r.cs[2].running) << r.log(0) << r.log(1) << r.log(2);
  ::kill(r.cs[1].pid, SIGKILL);
  const double waited = wait_all(r.cs, 8.0);
  EXPECT_LT(waited, 5.0) << "coupler detection + stop took " << waited << " s";
  EXPECT_EQ(r.cs[0].exit_code, 5);
  EXPECT_NE(r.cs[2].exit_code, 0);
  EXPECT_NE(r.log(0).find("fluid (scripted_fluid, pid " + std::to_string(r.cs[1].pid) + ")"), std::string::npos)
      << r.log(0);
  EXPECT_NE(r.log(2).find("fluid (scripted_fluid"), std::string::npos) << r.log(2);  // the solid is told who
  EXPECT_FALSE(process_with_argument(r.dir.string()));
  std::cout << "[ info ] killed fluid: coupler and solid stopped after " << waited << " s\n";
}

TEST(CouplingProcesses, ProtocolTranscriptOfTheFirstCycles) {
  // Deterministic scripted peers, 3 cycles; any change of what crosses the wire changes this text.
  // Regenerate on purpose with COSIM_UPDATE_TRANSCRIPT=1 and review the diff.
  const fs::path dir = test_dir("transcript");
  const fs::path scene = write_scene(dir, "  mode: robin\n  time: {end: 3.0e-4}\n  output: {interval: 2.0e-4}\n");
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  const fs::path got = dir / "transcript.txt";
  std::vector<Child> cs{
      child("coupler", coupler_args(ep, scene, dir / "out", {"--transcript", got.string()}), dir),
      child("fluid", peer_args("fluid", ep, scene, {"--phases", "2", "--pressure-gradient", "1e4"}), dir),
      child("solid", peer_args("solid", ep, scene, {"--impedance", "1000", "--velocity", "2"}), dir)};
  for (auto& c : cs) launcher::start(c);
  wait_all(cs, 20);
  for (auto& c : cs) ASSERT_EQ(c.exit_code, 0) << c.name << ": " << read_file(c.log);
  const fs::path expected = fs::path(COSIM_SOURCE_DIR) / "tests/coupling/data/transcript_scripted.txt";
  if (std::getenv("COSIM_UPDATE_TRANSCRIPT")) fs::copy_file(got, expected, fs::copy_options::overwrite_existing);
  const std::string a = read_file(expected), b = read_file(got);
  EXPECT_EQ(a, b) << "the protocol transcript changed: diff " << expected << " " << got
                  << " (COSIM_UPDATE_TRANSCRIPT=1 accepts it)";
}

TEST(CouplingProcesses, HungPeerDetectedByHeartbeatTimeout) {
  // SIGSTOP: the connection stays open but nothing answers; declared dead after the scene's timeout (2 s here).
  ThreeProcs r("hung", "  time: {end: 1.0e9}\n  timeout: 2.0\n");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_TRUE(r.cs[0].running && r.cs[2].running) << r.log(0);
  ::kill(r.cs[2].pid, SIGSTOP);
  const auto t0 = std::chrono::steady_clock::now();
  while (r.cs[0].running && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(6)) {
    launcher::poll(r.cs[0]);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(r.cs[0].running);
  EXPECT_LT(waited, 2.6);
  EXPECT_NE(r.log(0).find("solid (scripted_solid, pid " + std::to_string(r.cs[2].pid) +
                          ") declared dead: no message "
                          "or heartbeat for 2.0 s (timeout 2 s)"),
            std::string::npos)
      << r.log(0);
  ::kill(r.cs[2].pid, SIGKILL);
  wait_all(r.cs, 5);
  EXPECT_NE(r.cs[1].exit_code, 0);
  EXPECT_FALSE(process_with_argument(r.dir.string()));
}

TEST(CouplingProcesses, ExchangeLatencyAgainstABareRoundTrip) {
  // Bare ZeroMQ DEALER/ROUTER round trip over ipc:// in one process, then 2000 coupled cycles of the scripted
  // peers (4 sequential exchanges per cycle: decision->faces, faces->samples, samples->states, states->dt).
  const fs::path dir = test_dir("latency");
  const std::string ep = "ipc://" + (dir / "bare.sock").string();
  double bare = 0;
  {
    coupling::ZmqContext ctx;
    coupling::ZmqSocket router(ctx, coupling::ZmqSocket::Type::Router), dealer(ctx, coupling::ZmqSocket::Type::Dealer);
    router.bind(ep);
    dealer.connect(ep);
    std::thread echo([&] {
      coupling::Frames f;
      for (int i = 0; i < 2100; ++i) {
        router.receive(f, 5000);
        router.send(f);
      }
    });
    coupling::Frames f;
    std::chrono::steady_clock::time_point t0;
    for (int i = 0; i < 2100; ++i) {
      if (i == 100) t0 = std::chrono::steady_clock::now();
      dealer.send({std::string(64, 'x')});
      dealer.receive(f, 5000);
    }
    bare = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / 2000;
    echo.join();
  }
  ThreeProcs r("latency", "  time: {end: 0.2}\n", {"--dt", "1e-4"}, {"--dt", "1e-4"});
  wait_all(r.cs, 30);
  ASSERT_EQ(r.cs[0].exit_code, 0) << r.log(0);
  const std::string s = read_file(r.dir / "out" / "coupler_summary.json");
  const auto at = s.find("\"comm\": ");
  ASSERT_NE(at, std::string::npos) << s;
  const double comm = std::stod(s.substr(at + 8));
  std::cout << "[ info ] bare round trip " << bare * 1e6 << " us; coupled cycle communication " << comm * 1e6
            << " us = " << comm / 4 * 1e6 << " us per exchange (" << comm / 4 / bare << "x bare)\n";
  EXPECT_LT(comm, 0.01);  // sanity: far below a millisecond per exchange on an idle machine
}

TEST(CouplingProcesses, ScriptedSolidSendsTheFacesItIsAskedFor) {
  // --faces 37: a 7-column grid of 1 cm quads (5 full rows and 2 faces) in the plane x = 0, normal +x, at rest; the
  // fluid's pressure 2e5 Pa on every face. The coupler's force -sum p A n and area-weighted centre count the faces.
  ThreeProcs r("grid_faces", "  mode: robin\n  time: {end: 1.0e-3}\n  timeout: 5.0\n", {"--pressure", "2e5"},
               {"--faces", "37", "--velocity", "0"});
  wait_all(r.cs, 20);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(r.cs[i].exit_code, 0) << r.cs[i].name << ":\n" << r.log(i);
  std::istringstream hist(read_file(r.dir / "out" / "interface_history.csv"));
  std::string line, last;
  int rows = 0;
  for (std::getline(hist, line); std::getline(hist, line); ++rows) last = line;
  ASSERT_EQ(rows, 11);  // cycle 0 (exchange only), then 1 ms in steps of the peers' 1e-4 s
  std::vector<double> v;
  std::istringstream cells(last);
  for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
  ASSERT_EQ(v.size(), 13u);
  EXPECT_NEAR(v[3], -2e5 * 37 * 1e-4, 1e-9);  // force_x [N]
  EXPECT_EQ(v[4], 0.0);
  EXPECT_EQ(v[5], 0.0);
  EXPECT_NEAR(v[9], 0.0, 1e-15);                         // centre_x: the plane x = 0
  EXPECT_NEAR(v[10], (106.0 / 37 + 0.5) * 0.01, 1e-12);  // columns: 5 x (0 + ... + 6) + 0 + 1
  EXPECT_NEAR(v[11], (80.0 / 37 + 0.5) * 0.01, 1e-12);   // rows: 7 x (0 + ... + 4) + 2 x 5
  EXPECT_NEAR(v[12], 2e5, 1e-9);
  // The solid's Faces message carries at least 37 x 12 doubles and the 8 x 7 vertices, and the coupler forwards it.
  const auto j = nlohmann::json::parse(read_file(r.dir / "out" / "coupler_summary.json"));
  const double cycles = j["cycles"].get<double>() + 1, least = 37 * 12 * 8 + 56 * 3 * 8 + 37 * 4;
  const double from_solid = j["message_bytes"]["solid"]["received"].get<double>() / cycles;
  EXPECT_GT(from_solid, least);
  EXPECT_LT(from_solid, least + 400);  // and little else: a DtProposal and the header
  EXPECT_GT(j["message_bytes"]["fluid"]["sent"].get<double>() / cycles, least);
}

TEST(CouplingProcesses, ScriptedFluidRefusesFaces) {
  const fs::path dir = test_dir("fluid_faces");
  const auto [rc, out] = run_shell(dir, bin("cosim_scripted_peer").string() +
                                            " --role fluid --faces 3 --endpoint ipc://" + (dir / "x.sock").string());
  EXPECT_EQ(rc, 2) << out;
  EXPECT_NE(out.find("--faces is an option of --role solid"), std::string::npos) << out;
}
