// Bare ZeroMQ round trip between two processes, the yardstick of the coupled cycle's communication
// (bench/coupled/run_overhead.py). fork() splits the program before any ZeroMQ context exists: the child is
// the coupler's side (ROUTER, bound, echoes every request with a reply of the size the request asks for),
// the parent the solver's side (DEALER, connected, measures). Both use the project's wrapper
// common/coupling/zmq_socket.h, as the coupler and the client library do, so the same zmq_poll +
// zmq_msg_recv path is measured; nothing else (no protobuf, no validation, no solver) is on the way.
//
// Measurements, over ipc:// and tcp://127.0.0.1:
//   small      64 B request, 64 B reply (as tests/coupling ExchangeLatencyAgainstABareRoundTrip)
//   cycle      the coupled cycle's critical path for --faces N interface faces (2D, one phase, segment
//              vertices): the three request/reply pairs of the six messages on it,
//                decision -> faces, faces -> samples, states -> proposal,
//              with the byte sizes of the real protobuf envelopes (encoded here with common/coupling/wire.h);
//              reported per cycle and per round trip.
//   cycle_pipelined  the pipelined cycle's critical path when the fluid is the slower solver: its one round trip
//              samples -> states (real sizes); decision and faces wait in the fluid's queue during its advance.
//   workW      64 B round trips where the echo side first computes W us (--work, default 100,1000), minus W:
//              the latency when the waiting side has been idle for W, as in a coupled cycle where every
//              process waits while another one works.
//   protocol   the whole cycle between three processes (coupler ROUTER + solid and fluid DEALERs): all nine
//              messages of a cycle (including those off the critical path: DtDecision to the fluid,
//              InterfaceStates to the solid, the solid's DtProposal), raw bytes of the real sizes; optional
//              busy work of the solvers (--protocol-work), subtracted from the reported time.
//   protocol_pipelined  the same nine messages in the pipelined order (coupling.scheme: pipelined, the default;
//              docs/protocol.md "Schemes"): the solid sends its DtProposal right after its faces, the fluid right
//              after its samples, so the coupler sends the next DtDecision as soon as it has sent the states and
//              the fluid's advance overlaps the solid's next step. The work subtracted is what the coupler's
//              CycleTiming::comm subtracts for this scheme, max(solid, fluid sampling + advance).
// Plus the in-process cost of the protobuf layer per cycle (copy + encode on the sender, decode + validate +
// from_pb on the receiver, for the six critical-path messages), part of which the coupled cycle's "comm"
// contains (encode, decode and validate fall between the busy intervals).
//
// Usage: coupled_zmq_round_trip [--faces N] [--count N] [--warmup N] [--transport ipc|tcp|both]
//                               [--work US,US,...] [--protocol-work S,FS,FA] [--patterns LIST] [--json]
// LIST: any of small,cycle,cycle_pipelined,work,protocol,protocol_pipelined (default: all).
// Prints a table; with --json one JSON object per line instead (read by run_overhead.py).
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupling/wire.h"
#include "common/coupling/zmq_socket.h"

using namespace cosim;
using coupling::Frames;
using coupling::ZmqContext;
using coupling::ZmqSocket;
namespace pb = coupling::pb;

namespace {

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

std::string join_sizes(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s;
}

// A request: 8 bytes "reply size", 8 bytes "microseconds of work before the reply", then padding up to the
// request size; a reply size of 0xFF..FF means "stop".
std::string request(std::size_t size, std::size_t reply, std::uint64_t work_us = 0) {
  std::string r(std::max<std::size_t>(size, 16), 'q');
  std::uint64_t v = reply;
  std::memcpy(r.data(), &v, 8);
  std::memcpy(r.data() + 8, &work_us, 8);
  return r;
}

// Stands in for a solver's step: keeps the CPU busy (no sleep) for us microseconds.
void busy_work(std::uint64_t us) {
  if (us == 0) return;
  const double end = now_s() + 1e-6 * static_cast<double>(us);
  volatile double x = 1.0;
  while (now_s() < end)
    for (int i = 0; i < 100; ++i) x = x * 1.0000001 + 1e-9;
}

// Child: bind the ROUTER, tell the parent the bound endpoint through the pipe, echo until "stop".
[[noreturn]] void serve(const std::string& endpoint, int pipe_w) {
  int code = 0;
  try {
    ZmqContext ctx;
    ZmqSocket router(ctx, ZmqSocket::Type::Router);
    router.set_router_mandatory();
    router.bind(endpoint);
    const std::string bound = router.last_endpoint() + "\n";
    if (::write(pipe_w, bound.data(), bound.size()) < 0) std::_Exit(3);
    ::close(pipe_w);
    Frames in;
    std::string reply;
    for (;;) {
      if (!router.receive(in, 20000)) {
        code = 2;
        break;
      }
      if (in.size() != 2 || in[1].size() < 16) {
        code = 4;
        break;
      }
      std::uint64_t want = 0;
      std::memcpy(&want, in[1].data(), 8);
      if (want == ~std::uint64_t{0}) break;
      std::uint64_t work_us = 0;
      std::memcpy(&work_us, in[1].data() + 8, 8);
      busy_work(work_us);
      if (reply.size() != want) reply.assign(want, 'r');
      if (!router.send({in[0], reply}, 5000)) {
        code = 5;
        break;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "server: %s\n", e.what());
    code = 1;
  }
  std::_Exit(code);
}

struct Stats {
  double mean = 0, median = 0, p10 = 0, p90 = 0, min = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
  s.median = at(0.5);
  s.p10 = at(0.1);
  s.p90 = at(0.9);
  s.min = v.front();
  return s;
}

struct Pair {
  std::string name;
  std::size_t request, reply;
  std::uint64_t work_us = 0;  // the echo side works this long before replying
};

// The six messages on the coupled cycle's critical path, as the project encodes them, for n faces.
struct CycleMessages {
  pb::Envelope decision, faces, samples, states_fluid, states_solid, proposal;
  std::size_t bytes(const pb::Envelope& e) const { return coupling::encode(e).size(); }
};

CycleMessages make_cycle_messages(int n) {
  using coupling::Role;
  const std::string token(32, 't');  // the launcher's token is 32 hex digits
  CycleMessages m;
  m.decision = coupling::make_envelope(Role::Coupler, token, 1234, 0.0123);
  m.decision.mutable_dt_decision()->set_dt(1e-6);
  m.decision.mutable_dt_decision()->set_target_time(0.0123 + 1e-6);

  coupling::Faces f;
  f.dim = 2;
  f.count = n;
  f.nodes_per_face = 2;
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    f.centre.insert(f.centre.end(), {0.5 + 0.1 * std::cos(a), 0.5 + 0.1 * std::sin(a)});
    f.normal.insert(f.normal.end(), {std::cos(a), std::sin(a)});
    f.area.push_back(0.1 * 6.283185307179586 / n);
    f.velocity.insert(f.velocity.end(), {1e-3 * std::sin(3 * a), -2e-3 * std::cos(a)});
    f.normal_stress.push_back(-1e5 - 13.7 * i);
    f.impedance.push_back(3.6e7 + i);
    f.vertex_position.insert(f.vertex_position.end(), {0.5 + 0.1 * std::cos(a + 0.01), 0.5 + 0.1 * std::sin(a + 0.01)});
    f.face_vertex.insert(f.face_vertex.end(), {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>((i + 1) % n)});
  }
  m.faces = coupling::make_envelope(Role::Solid, token, 1234, 0.0123);
  coupling::to_pb(f, *m.faces.mutable_faces());

  coupling::FluidSamples s;
  s.count = n;
  s.phases = 1;
  for (int i = 0; i < n; ++i) {
    s.alpha.push_back(1.0);
    s.rho.push_back(1.2 + 1e-4 * i);
    s.normal_velocity.push_back(1e-3 * std::sin(0.1 * i));
    s.pressure.push_back(1e5 + 17.3 * i);
    s.impedance.push_back(413.0 + 0.01 * i);
    s.wetted.push_back(1);
  }
  m.samples = coupling::make_envelope(Role::Fluid, token, 1234, 0.0123);
  coupling::to_pb(s, *m.samples.mutable_samples());

  coupling::InterfaceStates st;
  st.count = n;
  st.phases = 1;
  st.pressure = s.pressure;
  st.normal_velocity = s.normal_velocity;
  m.states_fluid = coupling::make_envelope(Role::Coupler, token, 1234, 0.0123);
  coupling::to_pb(st, *m.states_fluid.mutable_states());
  coupling::InterfaceStates ss;
  ss.count = n;
  ss.phases = 0;
  ss.face_pressure = s.pressure;
  ss.face_normal_velocity = s.normal_velocity;
  ss.face_wetted = s.wetted;
  m.states_solid = coupling::make_envelope(Role::Coupler, token, 1234, 0.0123);
  coupling::to_pb(ss, *m.states_solid.mutable_states());

  m.proposal = coupling::make_envelope(Role::Fluid, token, 1234, 0.0123);
  m.proposal.mutable_dt_proposal()->set_dt(1.1e-6);
  return m;
}

// Round trips of `pattern` (one cycle = every pair once, in order) against a fresh echo child.
// Returns per-cycle seconds (cycles after warmup).
std::vector<double> measure(const std::string& endpoint, const std::vector<Pair>& pattern, int count, int warmup,
                            std::string& bound) {
  int fd[2];
  if (::pipe(fd) != 0) throw std::runtime_error("pipe");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork");
  if (pid == 0) {
    ::close(fd[0]);
    serve(endpoint, fd[1]);
  }
  ::close(fd[1]);
  std::string ep;
  char c;
  while (::read(fd[0], &c, 1) == 1 && c != '\n') ep += c;
  ::close(fd[0]);
  if (ep.empty()) throw std::runtime_error("the echo process did not bind " + endpoint);
  bound = ep;

  std::vector<double> out;
  {
    ZmqContext ctx;
    ZmqSocket dealer(ctx, ZmqSocket::Type::Dealer);
    dealer.connect(ep);
    std::vector<std::string> reqs;
    for (const auto& p : pattern) reqs.push_back(request(p.request, p.reply, p.work_us));
    Frames in;
    for (int i = 0; i < warmup + count; ++i) {
      const double t0 = now_s();
      for (std::size_t k = 0; k < pattern.size(); ++k) {
        if (!dealer.send({reqs[k]}, 5000)) throw std::runtime_error("send failed");
        if (!dealer.receive(in, 5000)) throw std::runtime_error("no reply within 5 s");
        if (in.size() != 1 || in[0].size() != pattern[k].reply) throw std::runtime_error("bad reply");
      }
      if (i >= warmup) out.push_back(now_s() - t0);
    }
    dealer.send({request(16, ~std::uint64_t{0})}, 1000);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("echo process ended with status {}", status));
  return out;
}

// The whole message pattern of a coupled cycle between three processes, as coupler/cycle.cpp and the two
// solver loops exchange it (docs/protocol.md), with raw bytes of the real sizes and no protobuf: the parent is
// the coupler (ROUTER, bound), two children are the solid and the fluid (DEALER, connected). Per cycle,
// sequential order:
//   coupler -> fluid, solid: DtDecision; solid works work[0] us, -> coupler: InterfaceFaces;
//   coupler -> fluid: InterfaceFaces; fluid works work[1] us (sampling), -> coupler: FluidSamples;
//   coupler -> fluid, solid: InterfaceStates; solid -> coupler: DtProposal; fluid works work[2] us (advance),
//   -> coupler: DtProposal.
// Pipelined order:
//   coupler -> fluid, solid: DtDecision; solid works work[0] us, -> coupler: InterfaceFaces, DtProposal;
//   coupler -> fluid: InterfaceFaces; fluid works work[1] us (sampling), -> coupler: FluidSamples, DtProposal;
//   coupler -> fluid, solid: InterfaceStates; the coupler has both proposals and sends the next DtDecision at
//   once, while the fluid works work[2] us (advance) after the states: the solid's next step overlaps it, and
//   the next faces wait in the fluid's queue. Proposals carry their own tag, so that the coupler can count them
//   whenever they arrive (as the coupler's per-solver inboxes keep them until expected).
// Returns per-cycle seconds (DtDecision sent .. the next DtDecision sent, as the coupler's wall) minus the work
// CycleTiming::comm subtracts: sequential work[0] + work[1] + work[2]; pipelined max(work[0], work[1] + work[2]).
struct ProtocolSizes {
  std::size_t decision, faces, samples, states_fluid, states_solid, proposal;
};

enum : std::uint64_t { kMsgData = 1, kMsgStop = 2, kMsgProposal = 3 };

std::string tagged(std::size_t size, std::uint64_t tag) {
  std::string r(std::max<std::size_t>(size, 8), 'p');
  std::memcpy(r.data(), &tag, 8);
  return r;
}

[[noreturn]] void protocol_peer(bool fluid, bool pipelined, int pipe_r, const ProtocolSizes& z,
                                const std::array<int, 3>& work) {
  int code = 0;
  try {
    std::string ep;
    char c;
    while (::read(pipe_r, &c, 1) == 1 && c != '\n') ep += c;
    ::close(pipe_r);
    ZmqContext ctx;
    ZmqSocket d(ctx, ZmqSocket::Type::Dealer);
    d.connect(ep);
    d.send({fluid ? "F" : "S"}, 5000);
    Frames in;
    const auto recv = [&]() -> bool {
      if (!d.receive(in, 20000) || in.size() != 1 || in[0].size() < 8) throw std::runtime_error("peer: no message");
      std::uint64_t tag = 0;
      std::memcpy(&tag, in[0].data(), 8);
      return tag != kMsgStop;
    };
    const std::string faces = tagged(z.faces, kMsgData), samples = tagged(z.samples, kMsgData),
                      proposal = tagged(z.proposal, pipelined ? kMsgProposal : kMsgData);
    for (;;) {
      if (!recv()) break;  // DtDecision or stop
      if (fluid && pipelined) {
        recv();  // InterfaceFaces
        busy_work(static_cast<std::uint64_t>(work[1]));
        d.send({samples}, 5000);
        d.send({proposal}, 5000);                        // from t^n, before the states
        recv();                                          // InterfaceStates
        busy_work(static_cast<std::uint64_t>(work[2]));  // the next DtDecision and faces queue up meanwhile
      } else if (fluid) {
        recv();  // InterfaceFaces
        busy_work(static_cast<std::uint64_t>(work[1]));
        d.send({samples}, 5000);
        recv();  // InterfaceStates
        busy_work(static_cast<std::uint64_t>(work[2]));
        d.send({proposal}, 5000);
      } else if (pipelined) {
        busy_work(static_cast<std::uint64_t>(work[0]));
        d.send({faces}, 5000);
        d.send({proposal}, 5000);
        recv();  // InterfaceStates
      } else {
        busy_work(static_cast<std::uint64_t>(work[0]));
        d.send({faces}, 5000);
        recv();  // InterfaceStates
        d.send({proposal}, 5000);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s peer: %s\n", fluid ? "fluid" : "solid", e.what());
    code = 1;
  }
  std::_Exit(code);
}

std::vector<double> measure_protocol(const std::string& endpoint, bool pipelined, const ProtocolSizes& z,
                                     const std::array<int, 3>& work, int count, int warmup) {
  int pf[2], ps[2];
  if (::pipe(pf) != 0 || ::pipe(ps) != 0) throw std::runtime_error("pipe");
  std::fflush(nullptr);
  const pid_t fpid = ::fork();
  if (fpid == 0) {
    ::close(pf[1]);
    ::close(ps[0]);
    ::close(ps[1]);
    protocol_peer(true, pipelined, pf[0], z, work);
  }
  const pid_t spid = ::fork();
  if (spid == 0) {
    ::close(ps[1]);
    ::close(pf[0]);
    ::close(pf[1]);
    protocol_peer(false, pipelined, ps[0], z, work);
  }
  ::close(pf[0]);
  ::close(ps[0]);
  std::vector<double> out;
  {
    ZmqContext ctx;
    ZmqSocket r(ctx, ZmqSocket::Type::Router);
    r.set_router_mandatory();
    r.bind(endpoint);
    const std::string ep = r.last_endpoint() + "\n";
    if (::write(pf[1], ep.data(), ep.size()) < 0 || ::write(ps[1], ep.data(), ep.size()) < 0)
      throw std::runtime_error("pipe write");
    ::close(pf[1]);
    ::close(ps[1]);
    std::string fid, sid;
    Frames in;
    while (fid.empty() || sid.empty()) {
      if (!r.receive(in, 20000) || in.size() != 2) throw std::runtime_error("no hello from the peers");
      (in[1] == "F" ? fid : sid) = in[0];
    }
    const std::string decision = tagged(z.decision, kMsgData), faces = tagged(z.faces, kMsgData),
                      states_f = tagged(z.states_fluid, kMsgData), states_s = tagged(z.states_solid, kMsgData);
    int proposals = 0;  // pipelined: DtProposals received in this cycle, whenever they came
    const auto expect = [&](const std::string& from) {
      for (;;) {
        if (!r.receive(in, 20000) || in.size() != 2 || in[1].size() < 8)
          throw std::runtime_error("protocol: no message");
        std::uint64_t tag = 0;
        std::memcpy(&tag, in[1].data(), 8);
        if (pipelined && tag == kMsgProposal && (in[0] == fid || in[0] == sid)) {
          ++proposals;
          continue;
        }
        if (in[0] != from) throw std::runtime_error("protocol: unexpected");
        return;
      }
    };
    const auto send = [&](const std::string& to, const std::string& m) {
      if (!r.send({to, m}, 5000)) throw std::runtime_error("protocol: cannot send");
    };
    const double work_s = 1e-6 * (pipelined ? std::max(work[0], work[1] + work[2]) : work[0] + work[1] + work[2]);
    // One clock reading per cycle, when its DtDecision goes out: a cycle lasts until the next one's (the coupler's
    // wall), so that nothing between two cycles is lost (in the pipelined order the fluid advances there).
    double t_open = 0;
    for (int i = 0; i < warmup + count; ++i) {
      const double t0 = now_s();
      if (i > warmup) out.push_back(t0 - t_open - work_s);
      t_open = t0;
      proposals = 0;
      send(fid, decision);
      send(sid, decision);
      expect(sid);  // faces
      send(fid, faces);
      expect(fid);  // samples
      send(fid, states_f);
      send(sid, states_s);
      for (; proposals < 2; ++proposals) {  // both proposals, in either order (pipelined: those not yet counted)
        std::uint64_t tag = 0;
        if (r.receive(in, 20000) && in.size() == 2 && in[1].size() >= 8) std::memcpy(&tag, in[1].data(), 8);
        if ((in[0] != fid && in[0] != sid) || tag != (pipelined ? kMsgProposal : kMsgData))
          throw std::runtime_error("protocol: no proposal");
      }
    }
    out.push_back(now_s() - t_open - work_s);  // the last cycle: until its last proposal
    send(fid, tagged(8, kMsgStop));
    send(sid, tagged(8, kMsgStop));
  }
  for (pid_t p : {fpid, spid}) {
    int status = 0;
    ::waitpid(p, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error(fmt::format("protocol peer ended with status {}", status));
  }
  return out;
}

// In-process protobuf layer of one cycle: for each of the six messages, sender to_pb-equivalent + encode and
// receiver decode + validate + from_pb. Seconds per cycle (median of `reps`).
double protobuf_seconds(const CycleMessages& m, int reps) {
  std::vector<double> t;
  std::string why;
  for (int r = 0; r < reps; ++r) {
    const double t0 = now_s();
    for (const pb::Envelope* e : {&m.decision, &m.faces, &m.faces, &m.samples, &m.states_fluid, &m.proposal}) {
      pb::Envelope copy = *e;  // stands in for the sender's to_pb (filling the message)
      const std::string bytes = coupling::encode(copy);
      auto d = coupling::decode(bytes, why);
      if (!d || !coupling::validate(*d).empty()) throw std::runtime_error("protobuf round trip failed: " + why);
      if (d->has_faces()) (void)coupling::from_pb(d->faces());
      if (d->has_samples()) (void)coupling::from_pb(d->samples());
      if (d->has_states()) (void)coupling::from_pb(d->states());
    }
    t.push_back(now_s() - t0);
  }
  return stats(t).median;
}

}  // namespace

std::vector<int> parse_list(const std::string& text) {
  std::vector<int> v;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t comma = text.find(',', at);
    const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    if (!item.empty()) v.push_back(std::stoi(item));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return v;
}

struct Pattern {
  std::string name, label;
  std::vector<Pair> pairs;
  int count;
  double work_s = 0;  // subtracted from the reported times (the echo side's work per cycle)
};

int main(int argc, char** argv) {
  int faces = 128, count = 5000, warmup = 500;
  std::string transport = "both", work_list = "100,1000", protocol_work = "0,0,0",
              which = "small,cycle,cycle_pipelined,work,protocol,protocol_pipelined";
  bool json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--faces") faces = std::stoi(next());
    else if (a == "--count") count = std::stoi(next());
    else if (a == "--warmup") warmup = std::stoi(next());
    else if (a == "--transport") transport = next();
    else if (a == "--work") work_list = next();
    else if (a == "--protocol-work") protocol_work = next();
    else if (a == "--patterns") which = next();
    else if (a == "--json") json = true;
    else {
      std::fprintf(stderr,
                   "usage: %s [--faces N] [--count N] [--warmup N] [--transport ipc|tcp|both] [--work US,US,...] "
                   "[--protocol-work SOLID_US,FLUID_SAMPLE_US,FLUID_ADVANCE_US] "
                   "[--patterns small,cycle,cycle_pipelined,work,protocol,protocol_pipelined] [--json]\n",
                   argv[0]);
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  if (faces < 1 || count < 10 || warmup < 0 || (transport != "ipc" && transport != "tcp" && transport != "both")) {
    std::fprintf(stderr, "bad arguments\n");
    return 2;
  }
  try {
    const CycleMessages m = make_cycle_messages(faces);
    const std::size_t b_dec = m.bytes(m.decision), b_faces = m.bytes(m.faces), b_samp = m.bytes(m.samples),
                      b_stf = m.bytes(m.states_fluid), b_prop = m.bytes(m.proposal);
    const auto wanted = [&](const std::string& p) {
      return ("," + which + ",").find("," + p + ",") != std::string::npos;
    };
    std::vector<Pattern> patterns;
    if (wanted("small"))
      patterns.push_back({"small", "64 B <-> 64 B, one round trip", {{"64 B <-> 64 B", 64, 64}}, count});
    if (wanted("cycle"))
      patterns.push_back({"cycle",
                          "cycle's 3 round trips (real sizes), per cycle",
                          {{"decision -> faces", b_dec, b_faces},
                           {"faces -> samples", b_faces, b_samp},
                           {"states -> proposal", b_stf, b_prop}},
                          count});
    // Pipelined scheme, fluid the slower solver: the only round trip on its path (the next decision and faces
    // are already in its queue when it has advanced).
    if (wanted("cycle_pipelined"))
      patterns.push_back({"cycle_pipelined",
                          "pipelined cycle's round trip samples -> states (real sizes), per cycle",
                          {{"samples -> states", b_samp, b_stf}},
                          count});
    // The echo side works W us before each reply while the measuring side waits (as the coupler waits for a
    // solver): round trip minus W shows what waking a waiting process costs.
    for (int w : parse_list(work_list)) {
      if (w <= 0 || !wanted("work")) continue;
      const int n = std::max(100, std::min(count, static_cast<int>(2e6 / (w + 50))));
      patterns.push_back({fmt::format("work{}", w),
                          fmt::format("64 B, echo works {} us first: round trip - {} us", w, w),
                          {{"work", 64, 64, static_cast<std::uint64_t>(w)}},
                          n,
                          1e-6 * w});
    }
    const double proto = protobuf_seconds(m, std::max(200, count / 10));
    if (!json) {
      std::printf(
          "bare ZeroMQ DEALER/ROUTER round trips between two processes (fork), wrapper "
          "common/coupling/zmq_socket.h; up to %d round trips after %d warm-up\n",
          count, warmup);
      std::printf(
          "message sizes for %d faces (2D, 1 phase): DtDecision %zu B, InterfaceFaces %zu B, FluidSamples "
          "%zu B, InterfaceStates %zu B (fluid) / %zu B (solid), DtProposal %zu B\n\n",
          faces, b_dec, b_faces, b_samp, b_stf, m.bytes(m.states_solid), b_prop);
      std::printf("| transport | pattern | mean [us] | median [us] | p10 [us] | p90 [us] | min [us] |\n");
      std::printf("|---|---|---|---|---|---|---|\n");
    }
    std::vector<std::string> transports;
    if (transport != "tcp") transports.push_back("ipc");
    if (transport != "ipc") transports.push_back("tcp");
    for (const auto& tr : transports) {
      const std::string ep =
          tr == "ipc" ? fmt::format("ipc:///tmp/cosim_zmq_rt_{}.sock", ::getpid()) : std::string("tcp://127.0.0.1:*");
      for (const auto& pat : patterns) {
        std::string bound;
        auto t = measure(ep, pat.pairs, pat.count, std::min(warmup, pat.count / 5), bound);
        for (double& x : t) x -= pat.work_s;
        const Stats s = stats(t);
        const double per = static_cast<double>(pat.pairs.size());
        std::vector<std::size_t> req, rep;
        for (const auto& p : pat.pairs) {
          req.push_back(p.request);
          rep.push_back(p.reply);
        }
        if (json) {
          std::printf(
              "{\"transport\": \"%s\", \"pattern\": \"%s\", \"faces\": %d, \"round_trips\": %zu, "
              "\"request_bytes\": [%s], \"reply_bytes\": [%s], \"work_s\": %.9e, \"count\": %d, "
              "\"mean_s\": %.9e, \"median_s\": %.9e, \"p10_s\": %.9e, \"p90_s\": %.9e, \"min_s\": %.9e}\n",
              tr.c_str(), pat.name.c_str(), faces, pat.pairs.size(), join_sizes(req).c_str(), join_sizes(rep).c_str(),
              pat.work_s, pat.count, s.mean, s.median, s.p10, s.p90, s.min);
        } else {
          std::printf("| %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f |\n", tr.c_str(), pat.label.c_str(), s.mean * 1e6,
                      s.median * 1e6, s.p10 * 1e6, s.p90 * 1e6, s.min * 1e6);
          if (pat.pairs.size() > 1)
            std::printf("| %s | same, per round trip | %.1f | %.1f | %.1f | %.1f | %.1f |\n", tr.c_str(),
                        s.mean / per * 1e6, s.median / per * 1e6, s.p10 / per * 1e6, s.p90 / per * 1e6,
                        s.min / per * 1e6);
        }
        std::fflush(stdout);
      }
      for (const bool pipelined : {false, true}) {
        const std::string name = pipelined ? "protocol_pipelined" : "protocol";
        if (!wanted(name)) continue;
        const auto pw = parse_list(protocol_work);
        if (pw.size() != 3) throw std::runtime_error("--protocol-work: three numbers");
        const std::array<int, 3> w{pw[0], pw[1], pw[2]};
        const ProtocolSizes z{b_dec, b_faces, b_samp, b_stf, m.bytes(m.states_solid), b_prop};
        const int n = std::max(100, std::min(count, static_cast<int>(3e6 / (w[0] + w[1] + w[2] + 300))));
        const Stats s = stats(measure_protocol(ep, pipelined, z, w, n, std::min(warmup, n / 5)));
        const int subtracted = pipelined ? std::max(w[0], w[1] + w[2]) : w[0] + w[1] + w[2];
        if (json) {
          std::printf(
              "{\"transport\": \"%s\", \"pattern\": \"%s\", \"faces\": %d, \"work_us\": [%d, %d, %d], "
              "\"work_s\": %.9e, \"count\": %d, \"mean_s\": %.9e, \"median_s\": %.9e, \"p10_s\": %.9e, "
              "\"p90_s\": %.9e, \"min_s\": %.9e}\n",
              tr.c_str(), name.c_str(), faces, w[0], w[1], w[2], 1e-6 * subtracted, n, s.mean, s.median, s.p10, s.p90,
              s.min);
        } else {
          std::printf(
              "| %s | whole cycle, 3 processes, 9 messages, %s order (work %d/%d/%d us: %d us subtracted) | "
              "%.1f | %.1f | %.1f | %.1f | %.1f |\n",
              tr.c_str(), pipelined ? "pipelined" : "sequential", w[0], w[1], w[2], subtracted, s.mean * 1e6,
              s.median * 1e6, s.p10 * 1e6, s.p90 * 1e6, s.min * 1e6);
        }
        std::fflush(stdout);
      }
    }
    if (json) std::printf("{\"pattern\": \"protobuf\", \"faces\": %d, \"median_s\": %.9e}\n", faces, proto);
    else
      std::printf(
          "\nprotobuf layer of one cycle in one process (encode, decode, validate, from_pb of the six "
          "messages): %.1f us\n",
          proto * 1e6);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coupled_zmq_round_trip: %s\n", e.what());
    return 1;
  }
  return 0;
}
