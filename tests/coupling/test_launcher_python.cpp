// `cosim run` with the Python rigid piston (python/rigid_piston.py) in place of solid_solver and a scripted fluid
// (test harness); the launcher's failure report and cleanup; the client's answer to a malformed message.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "common/coupling/client.h"
#include "common/coupling/wire.h"
#include "common/coupling/zmq_socket.h"
#include "coupling_test_util.h"

using namespace cosim;
using namespace cosim::test;

namespace {
int run_cosim(const std::string& args, const fs::path& log) {
  const std::string cmd = bin("cosim").string() + " run " + args + " > " + log.string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
std::string fluid_exe(const std::string& extra = "") {
  return "--fluid-exe '" + bin("cosim_scripted_peer").string() + " --role fluid --dt 1e-4 " + extra + "'";
}
std::string piston_exe() {
  return "--solid-exe '/usr/bin/python3 " + (python_dir() / "rigid_piston.py").string() +
         " --mass 2.5 --area 0.025 --left -1 --right 0'";
}
}  // namespace

TEST(CouplingLauncher, PythonPistonUnderAConstantPressureDifference) {
  // Scripted fluid: p = 1e5 + G x on each face, so F = (p_left - p_right) A = -G L A is constant (rigid
  // piston: impedance coupling gives the fluid pressure to the solid; the Robin condition would add the
  // scripted fluid's impedance): v = a t exactly, and symplectic Euler's
  // x differs from a t^2 / 2 by at most a t dt / 2. The pressures are not physical (negative on the left face),
  // so the coupler's pressure predictor (which keeps extrapolated pressures positive) is off.
  const fs::path dir = test_dir("piston");
  const fs::path scene =
      write_scene(dir, "  mode: impedance\n  time: {end: 0.01}\n  output: {interval: 0.005}\n  predictor: none\n");
  const fs::path run = dir / "run";
  const int rc = run_cosim(
      scene.string() + " --out " + run.string() + " " + fluid_exe("--pressure-gradient 1e5") + " " + piston_exe(),
      dir / "cosim.log");
  ASSERT_EQ(rc, 0) << read_file(dir / "cosim.log") << read_file(run / "solid.log") << read_file(run / "coupler.log");
  std::ifstream in(run / "solid" / "piston.csv");
  std::string header, line;
  std::getline(in, header);
  int rows = 0;
  const double a = -1e5 * 1.0 * 0.025 / 2.5, dt = 1e-4;
  while (std::getline(in, line)) {
    double t, x, v, f;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &x, &v, &f), 4) << line;
    EXPECT_NEAR(v, a * t, 1e-9 + 1e-6 * std::abs(a * t)) << line;
    EXPECT_NEAR(x, 0.5 * a * t * t, 1e-12 + 0.5 * std::abs(a) * t * dt) << line;
    if (t > 0) { EXPECT_GT(std::abs(x), 0.5 * std::abs(a) * t * t * 0.99) << line; }
    ++rows;
  }
  EXPECT_EQ(rows, 3);  // t = 0, 0.005, 0.01
  EXPECT_TRUE(fs::exists(run / "scene.yaml"));
  EXPECT_TRUE(fs::exists(run / "coupler" / "interface_history.csv"));
}

TEST(CouplingLauncher, FailingProcessIsNamedAndNothingIsLeftRunning) {
  const fs::path dir = test_dir("launch_fail");
  const fs::path scene = write_scene(dir, "  time: {end: 1.0e9}\n");
  const fs::path run = dir / "run";
  const int rc = run_cosim(
      scene.string() + " --out " + run.string() + " --tcp " + fluid_exe("--protocol-version 6") + " " + piston_exe(),
      dir / "cosim.log");
  const std::string log = read_file(dir / "cosim.log");
  EXPECT_NE(rc, 0);
  EXPECT_NE(log.find("failed with exit code"), std::string::npos) << log;
  EXPECT_NE(log.find("protocol version 6"), std::string::npos) << log;  // the last log lines are shown
  EXPECT_NE(read_file(run / "launch.json").find("tcp://127.0.0.1:"), std::string::npos);
  EXPECT_FALSE(process_with_argument(run.string()));
}

// A solver that keeps heartbeating but stops answering (a hung step) is stopped at the step timeout, named with
// the message it owes, and nothing is left running; the cause is in run_summary.json.
TEST(CouplingLauncher, APeerThatHeartbeatsButNeverAnswersIsStoppedAtTheStepTimeout) {
  const fs::path dir = test_dir("hung_peer");
  const fs::path scene = write_scene(dir, "  time: {end: 1.0e9}\n  step_timeout: 1.5\n");
  const fs::path run = dir / "run";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc =
      run_cosim(scene.string() + " --out " + run.string() + " " + fluid_exe("--hang-after 5") + " " + piston_exe(),
                dir / "cosim.log");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string log = read_file(dir / "cosim.log"), summary = read_file(run / "run_summary.json");
  std::printf("hung fluid: cosim exit %d after %.1f s\n", rc, wall);
  EXPECT_NE(rc, 0);
  EXPECT_NE(log.find("sends heartbeats but has not sent"), std::string::npos) << log;
  EXPECT_NE(log.find("coupling.step_timeout 1.5 s"), std::string::npos) << log;
  EXPECT_NE(summary.find("has not sent"), std::string::npos) << summary;
  EXPECT_LT(wall, 15.0);  // the timeout and a clean stop, not the heartbeat's silence (there is none)
  EXPECT_FALSE(process_with_argument(run.string()));
}

// A mistyped command or option is named, with the closest valid one, before anything else is checked; exit 2.
// --version answers on every executable.
TEST(CouplingLauncher, UnknownCommandsAndOptionsAreNamedWithASuggestionAndVersionAnswers) {
  const fs::path dir = test_dir("cli_words");
  const auto run_exe = [&](const std::string& cmd) {
    const int rc = std::system((cmd + " > " + (dir / "out.log").string() + " 2>&1").c_str());
    return std::pair{WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_file(dir / "out.log")};
  };
  auto [rc, log] = run_exe(bin("cosim").string() + " frobnicate x.yaml");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: unknown command 'frobnicate' (commands: check, run, view)"), std::string::npos) << log;
  std::tie(rc, log) = run_exe(bin("cosim").string() + " rn x.yaml");
  EXPECT_NE(log.find("unknown command 'rn' (did you mean 'run'?)"), std::string::npos) << log;
  std::tie(rc, log) = run_exe(bin("cosim").string() + " run x.yaml --output y");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("cosim: unknown option '--output' (did you mean '--out'?)"), std::string::npos) << log;
  for (const char* exe : {"fluid_solver", "solid_solver"}) {
    std::tie(rc, log) = run_exe(bin(exe).string() + " x.yaml --output y");
    EXPECT_EQ(rc, 2) << exe;
    EXPECT_NE(log.find(std::string(exe) + ": unknown option '--output' (did you mean '--out'?)"), std::string::npos)
        << log;
  }
  // --version on every executable: the version and the commit the build came from
  for (const char* exe : {"cosim", "fluid_solver", "solid_solver", "coupler"}) {
    std::tie(rc, log) = run_exe(bin(exe).string() + " --version");
    EXPECT_EQ(rc, 0) << exe;
    EXPECT_EQ(log.rfind(std::string(exe) + " 0.", 0), 0u) << log;
    EXPECT_NE(log.find("(git "), std::string::npos) << log;
  }
  std::tie(rc, log) = run_exe(bin("coupler").string() + " x.yaml --endpiont ipc://z");
  EXPECT_EQ(rc, 2);
  EXPECT_NE(log.find("coupler: unknown option '--endpiont' (did you mean '--endpoint'?)"), std::string::npos) << log;
}

TEST(CouplingLauncher, SceneWithoutSolidRunsTheFluidAlone) {
  const fs::path dir = test_dir("fluid_only");
  const fs::path scene = dir / "scene.yaml";
  std::ofstream(scene) << "name: alone\nfluid: {dummy: 1}\n";
  const fs::path run = dir / "run";
  // /bin/echo stands in for fluid_solver: it prints the command line it got.
  const int rc = run_cosim(scene.string() + " --out " + run.string() + " --fluid-exe /bin/echo", dir / "cosim.log");
  EXPECT_EQ(rc, 0) << read_file(dir / "cosim.log");
  const std::string fl = read_file(run / "fluid.log");
  EXPECT_NE(fl.find("scene.yaml --out"), std::string::npos) << fl;
  EXPECT_EQ(fl.find("--coupler"), std::string::npos) << fl;
  EXPECT_FALSE(fs::exists(run / "coupler.log"));
}

TEST(CouplingClient, MalformedMessageFromTheCouplerGetsAnErrorReply) {
  // A fake coupler answers the Hello with garbage: the client replies Error and throws ProtocolError.
  const fs::path dir = test_dir("client_malformed");
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  coupling::ZmqContext ctx;
  coupling::ZmqSocket router(ctx, coupling::ZmqSocket::Type::Router);
  router.bind(ep);
  std::string client_error;
  std::thread t([&] {
    try {
      coupling::ClientOptions o;
      o.endpoint = ep;
      o.token = "tok";
      o.connect_timeout = 5.0;
      coupling::Client c(o);
    } catch (const coupling::ProtocolError& e) { client_error = e.what(); } catch (const std::exception& e) {
      client_error = std::string("wrong exception: ") + e.what();
    }
  });
  coupling::Frames hello, reply;
  ASSERT_TRUE(router.receive(hello, 5000));
  router.send({hello[0], "not protobuf \xff\xff"});
  ASSERT_TRUE(router.receive(reply, 5000));
  t.join();
  EXPECT_EQ(client_error, "fluid: malformed message (15 bytes): not a cosim Envelope");
  std::string why;
  auto e = coupling::decode(reply.at(1), why);
  ASSERT_TRUE(e && e->has_error()) << why;
  EXPECT_EQ(e->error().reason(), "malformed message (15 bytes): not a cosim Envelope");
}

TEST(CouplingClient, SilentCouplerIsDeclaredDead) {
  // A coupler that welcomes and then never answers: next() throws PeerLost after the Welcome's timeout.
  const fs::path dir = test_dir("client_silent");
  const std::string ep = "ipc://" + (dir / "c.sock").string();
  coupling::ZmqContext ctx;
  coupling::ZmqSocket router(ctx, coupling::ZmqSocket::Type::Router);
  router.bind(ep);
  std::thread t([&] {
    coupling::Frames hello;
    ASSERT_TRUE(router.receive(hello, 5000));
    coupling::pb::Envelope w = coupling::make_envelope(coupling::Role::Coupler, "tok", 0, 0.0);
    w.mutable_welcome()->set_accepted(true);
    w.mutable_welcome()->set_timeout(1.0);
    w.mutable_welcome()->set_heartbeat_interval(0.1);
    router.send({hello[0], coupling::encode(w)});
  });
  coupling::ClientOptions o;
  o.endpoint = ep;
  o.token = "tok";
  o.role = coupling::Role::Solid;
  coupling::Client c(o);
  t.join();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    c.next();
    FAIL() << "no exception";
  } catch (const coupling::PeerLost& e) {
    EXPECT_NE(std::string(e.what()).find("coupler at " + ep + " declared dead"), std::string::npos) << e.what();
  }
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The Welcome's 1 s timeout, plus the heartbeat checks' granularity and a loaded machine's scheduling (2.2 s
  // seen with six processes on the two cores), well inside the 5 s in which a silent peer must be noticed.
  EXPECT_LT(waited, 2.5);
  EXPECT_GT(waited, 0.9);
}

// A solver that goes on after the others ended is stopped only once it has written nothing to its output folder for
// the launcher's grace (COSIM_END_GRACE_S, 1 s here): one still writing its last output for 3 s completes the run,
// one silent for 3 s is stopped and named.
TEST(CouplingLauncher, ASolverStillWritingAfterTheOthersEndedIsWaitedFor) {
  for (const bool writing : {true, false}) {
    const fs::path dir = test_dir(writing ? "late_writer" : "late_silent");
    const fs::path scene = write_scene(dir, "  mode: impedance\n  time: {end: 0.002}\n  predictor: none\n");
    // The piston, then 3 s of appending to a file in its --out folder every 0.25 s (or of silence).
    const fs::path wrapper = dir / "late_solid.sh";
    std::ofstream(wrapper) << "#!/bin/sh\n/usr/bin/python3 " << (python_dir() / "rigid_piston.py").string()
                           << " --mass 2.5 --area 0.025 --left -1 --right 0 \"$@\" || exit $?\n"
                           << "out=; prev=; for a in \"$@\"; do [ \"$prev\" = --out ] && out=$a; prev=$a; done\n"
                           << (writing ? "i=0; while [ $i -lt 12 ]; do echo $i >> \"$out/last_output.txt\"; sleep "
                                         "0.25; i=$((i+1)); done\n"
                                       : "sleep 3\n");
    fs::permissions(wrapper, fs::perms::owner_all);
    const fs::path run = dir / "run";
    ::setenv("COSIM_END_GRACE_S", "1", 1);
    const int rc =
        run_cosim(scene.string() + " --out " + run.string() + " " + fluid_exe() + " --solid-exe " + wrapper.string(),
                  dir / "cosim.log");
    ::unsetenv("COSIM_END_GRACE_S");
    const std::string summary = read_file(run / "run_summary.json");
    if (writing) {
      EXPECT_EQ(rc, 0) << read_file(dir / "cosim.log");
      EXPECT_NE(summary.find("\"status\": \"completed\""), std::string::npos) << summary;
    } else {
      EXPECT_EQ(rc, 1) << read_file(dir / "cosim.log");
      EXPECT_NE(summary.find("solid still running 1 s after the others ended, writing nothing"), std::string::npos)
          << summary;
    }
  }
}
