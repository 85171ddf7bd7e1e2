#include "coupler/hub.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/app/run_driver.h"
#include "common/coupling/endpoints.h"
#include "common/coupling/errors.h"
#include "common/coupling/wire.h"
#include "coupler/owner_socket.h"

namespace cosim::coupler {

using coupling::PeerLost;
using coupling::ProtocolError;
using coupling::Role;
namespace pb = coupling::pb;

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
const std::array<Role, 2> kRoles{Role::Fluid, Role::Solid};
// A pipelined solid runs one step ahead (faces, proposal); more than this waiting means a peer ignores the cycle.
constexpr std::size_t kMaxAhead = 16;
}  // namespace

std::string Peer::describe(Role r) const {
  if (program.empty()) return coupling::role_name(r);
  return fmt::format("{} ({}, pid {})", coupling::role_name(r), program, pid);
}

Hub::Hub(const HubOptions& o, Transcript* transcript) : opt_(o), transcript_(transcript) {
  sock_.set_router_mandatory();
  sock_.set_max_message_size(static_cast<std::int64_t>(o.max_message_bytes));
  bound_ = bind_owner_only(sock_, o.endpoint);
  beats_ = std::make_unique<HeartbeatService>(ctx_, coupling::heartbeat_bind_endpoint(bound_), o.token,
                                              o.heartbeat_interval);
}

Hub::~Hub() {
  try {
    sock_.set_linger(1000);  // deliver the last Stop / Error
  } catch (...) {}
  remove_socket_file(bound_);
}

void Hub::reply_error(const std::string& id, const std::string& reason) {
  pb::Envelope e = coupling::make_envelope(Role::Coupler, opt_.token, cycle_, time_);
  e.mutable_error()->set_reason(reason);
  sock_.send({id, coupling::encode(e)}, 200);
}

void Hub::fail_peer(Role r, const std::string& what) {
  const std::string msg = fmt::format("{} {}", peer(r).describe(r), what);
  blame(r);
  reply_error(peer(r).id, msg);
  throw ProtocolError(msg);
}

std::string Hub::check_hello(const pb::Envelope& e) const {
  const auto& h = e.header();
  const auto& hello = e.hello();
  if (h.protocol_version() != coupling::kProtocolVersion)
    return fmt::format("protocol version {} of {}, the coupler speaks version {}", h.protocol_version(),
                       hello.program().empty() ? "the peer" : hello.program(), coupling::kProtocolVersion);
  if (hello.role() != pb::ROLE_FLUID && hello.role() != pb::ROLE_SOLID)
    return fmt::format("Hello.role: {}, expected fluid or solid", pb::Role_Name(hello.role()));
  if (h.token() != opt_.token)
    return "wrong run token (this process was not started for this run: a solver takes the run's token from "
           "$COSIM_TOKEN, which cosim run sets, or from --token when started by hand)";
  if (hello.scene_hash() != opt_.scene_hash)
    return fmt::format("scene hash {} differs from the coupler's {} (different scene file or --set overrides)",
                       hello.scene_hash(), opt_.scene_hash);
  if (hello.restarted_from() != opt_.restarted_from) {
    const auto start = [](long cycle) {
      return cycle == 0 ? std::string("a fresh start") : fmt::format("the checkpoint of cycle {}", cycle);
    };
    return fmt::format("it resumes from {}, the run from {} (every process must start from the same set)",
                       start(hello.restarted_from()), start(opt_.restarted_from));
  }
  if (hello.phase_min_pressure_size() != 0) {
    if (hello.phase_min_pressure_size() != hello.phase_names_size())
      return fmt::format("Hello.phase_min_pressure: {} values for {} phase_names, expected one per phase",
                         hello.phase_min_pressure_size(), hello.phase_names_size());
    for (int k = 0; k < hello.phase_min_pressure_size(); ++k)
      if (!std::isfinite(hello.phase_min_pressure(k)))
        return fmt::format("Hello.phase_min_pressure[{}]: {}, expected a finite pressure [Pa]", k,
                           hello.phase_min_pressure(k));
  }
  if (hello.ranks() > coupling::kMaxHelloRanks)
    return fmt::format("Hello.ranks: {}, expected the number of MPI ranks the solver speaks for (1 to {}; 0: 1)",
                       hello.ranks(), coupling::kMaxHelloRanks);
  const Role r = coupling::from_pb(hello.role());
  if (peer(r).connected)
    return fmt::format("this run already has a {}: {}", coupling::role_name(r), peer(r).describe(r));
  return "";
}

bool Hub::poll_once(int timeout_ms, Incoming& out) {
  coupling::Frames frames;
  const double t0 = now_s();
  const bool got = sock_.receive(frames, timeout_ms);
  wait_ += now_s() - t0;
  if (!got || frames.empty()) return false;
  const std::string id = frames[0];
  Role known = Role::Coupler;  // Coupler: not a connected peer's data connection
  for (Role r : kRoles)
    if (peer(r).connected && peer(r).id == id) known = r;
  // A stranger's message: answered and logged within the flood limit, else dropped (StrangerLimit).
  bool log_stranger = false;
  const auto admit_stranger = [&] {
    if (const std::string line = strangers_.summary(now_s()); !line.empty()) spdlog::warn("{}", line);
    return strangers_.admit(now_s(), log_stranger);
  };
  const auto fail_or_ignore = [&](const std::string& why) {
    if (known != Role::Coupler) fail_peer(known, "sent a " + why);
    if (!admit_stranger()) return false;
    if (log_stranger) spdlog::warn("ignored a message from an unknown connection: {}", why);
    reply_error(id, why);
    return false;
  };
  if (frames.size() != 2) return fail_or_ignore(fmt::format("malformed message of {} frames", frames.size() - 1));
  std::string why;
  auto e = coupling::decode(frames[1], why);
  if (!e) return fail_or_ignore(why);
  const auto& h = e->header();

  if (e->has_heartbeat()) {  // heartbeats belong on the heartbeat endpoint (Welcome.heartbeat_endpoint)
    if (h.token() != opt_.token) return fail_or_ignore("heartbeat with a wrong run token");
    // Ignored (they do not keep the peer alive), said once per peer: a solver that beats here is declared dead
    // when a step outlasts the timeout, and the log then tells why.
    bool& said = known == Role::Coupler ? stranger_beat_said_ : peer(known).beats_on_data;
    if (!said)
      spdlog::warn(
          "{} sent a Heartbeat on the data connection, where heartbeats are ignored: they go to the "
          "heartbeat connection, Welcome.heartbeat_endpoint = {} (docs/protocol.md, Sockets); without them "
          "a step longer than the timeout ({:g} s) is taken for a dead peer",
          known == Role::Coupler ? "a connection that has not said Hello" : peer(known).describe(known),
          beats_->endpoint(), opt_.timeout);
    said = true;
    return false;
  }
  if (e->has_hello() && known == Role::Coupler) {
    const std::string reason = check_hello(*e);
    pb::Envelope w = coupling::make_envelope(Role::Coupler, h.token(), 0, 0.0);
    auto* welcome = w.mutable_welcome();
    welcome->set_accepted(reason.empty());
    welcome->set_reason(reason);
    welcome->set_heartbeat_interval(opt_.heartbeat_interval);
    welcome->set_heartbeat_endpoint(beats_->endpoint());
    welcome->set_timeout(opt_.timeout);
    welcome->set_mode(coupling::to_pb(opt_.mode));
    welcome->set_scheme(coupling::to_pb(opt_.scheme));
    if (!reason.empty()) {
      const bool own = !handshake_done_ && h.token() == opt_.token;  // the run's own solver, misconfigured
      if (!own && !admit_stranger()) return false;
      sock_.send({id, coupling::encode(w)}, 500);
      const std::string who = e->hello().program().empty() ? "a peer" : e->hello().program();
      const std::string msg = fmt::format("refused {} (pid {}): {}", who, e->hello().pid(), reason);
      // A Hello without this run's token is a stranger's (the launcher gives the run's own solvers the token):
      // refused and logged, the run goes on. One of the run's own solvers refused (its version, its scene) ends
      // the start-up, and any Hello once the run is going is refused.
      if (own) {
        const auto role = e->hello().role();
        if (role == pb::ROLE_FLUID || role == pb::ROLE_SOLID) blame(coupling::from_pb(role));
        throw coupling::Refused(msg);
      }
      if (log_stranger) spdlog::warn("{}; the run goes on", msg);
      return false;
    }
    Peer& p = peer(coupling::from_pb(e->hello().role()));
    p.connected = true;
    p.id = id;
    p.program = e->hello().program();
    p.pid = e->hello().pid();
    p.ranks = coupling::hello_ranks(e->hello());
    p.phase_names.assign(e->hello().phase_names().begin(), e->hello().phase_names().end());
    p.phase_min_pressure.assign(e->hello().phase_min_pressure().begin(), e->hello().phase_min_pressure().end());
    p.last_seen = now_s();
    beats_->admit(coupling::from_pb(e->hello().role()));
    p.hello = *e;
    p.welcome = w;
    if (!sock_.send({id, coupling::encode(w)}, 500)) {
      blame(coupling::from_pb(e->hello().role()));
      throw PeerLost(p.describe(coupling::from_pb(e->hello().role())) + " vanished during the handshake");
    }
    spdlog::info("{} connected, speaking for {} MPI rank(s)", p.describe(coupling::from_pb(e->hello().role())),
                 p.ranks);
    return false;
  }
  if (known == Role::Coupler) return fail_or_ignore(fmt::format("{} before Hello", coupling::body_name(*e)));

  Peer& p = peer(known);
  p.last_seen = now_s();
  if (h.protocol_version() != coupling::kProtocolVersion)
    fail_peer(known, fmt::format("sent {} with protocol version {}, expected {}", coupling::body_name(*e),
                                 h.protocol_version(), coupling::kProtocolVersion));
  if (h.token() != opt_.token) fail_peer(known, fmt::format("sent {} with a wrong run token", coupling::body_name(*e)));
  if (e->has_error() || e->has_stop()) blame(known);
  if (e->has_error()) throw PeerLost(fmt::format("{} reported an error: {}", p.describe(known), e->error().reason()));
  if (e->has_stop()) throw PeerLost(fmt::format("{} stopped: {}", p.describe(known), e->stop().reason()));
  std::string problem = coupling::validate(*e);
  if (problem.empty() && e->has_samples())
    problem = coupling::validate_sample_pressures(e->samples(), p.phase_min_pressure, p.phase_names);
  if (!problem.empty()) fail_peer(known, "sent an invalid message: " + problem);
  p.busy += std::max(0.0, h.busy_seconds());
  p.bytes_received += static_cast<double>(frames[1].size());
  p.output += std::clamp(h.output_seconds(), 0.0, std::max(0.0, h.busy_seconds()));
  out = {known, std::move(*e)};
  return true;
}

void Hub::beat_and_check() {
  // The heartbeats themselves go on the HeartbeatService's thread; here the verdict on what it heard.
  const double t = now_s();
  for (Role r : kRoles) {
    const Peer& p = peer(r);
    if (!p.connected) continue;
    if (const std::string why = beats_->lost(r); !why.empty()) {
      blame(r);
      throw PeerLost(fmt::format("{} declared dead: {}", p.describe(r), why));
    }
    const double heard = std::max(p.last_seen, beats_->last_heard(r));
    if (t - heard > opt_.timeout) {
      blame(r);
      throw PeerLost(fmt::format("{} declared dead: no message or heartbeat for {:.1f} s (timeout {:g} s){}",
                                 p.describe(r), t - heard, opt_.timeout,
                                 p.beats_on_data ? "; it sent its heartbeats on the data connection, not to "
                                                   "Welcome.heartbeat_endpoint"
                                                 : ""));
    }
  }
}

double Hub::step_limit(Role r) const {
  if (opt_.step_timeout > 0) return opt_.step_timeout;
  return std::max(kAutoStepFloor, kAutoStepFactor * peer(r).longest_answer);
}

Hub::Incoming Hub::next_data(const std::string& waiting_for, Role from, double since) {
  Incoming in;
  for (;;) {
    if (app::interrupted()) throw coupling::CouplingError("coupler interrupted (SIGINT/SIGTERM)");
    beat_and_check();
    // A peer that heartbeats but does not answer (a hung solver loop) is stopped too, naming what it owes.
    const double waited = now_s() - since, limit = step_limit(from);
    if (waited > limit) {
      blame(from);
      throw PeerLost(fmt::format(
          "{} sends heartbeats but has not sent {} for {:.1f} s (coupling.step_timeout {})", peer(from).describe(from),
          waiting_for, waited,
          opt_.step_timeout > 0 ? fmt::format("{:g} s", opt_.step_timeout) : fmt::format("automatic: {:g} s", limit)));
    }
    if (poll_once(50, in)) return in;
  }
}

void Hub::handshake() {
  const double deadline = now_s() + opt_.connect_timeout;
  Incoming in;
  while (!peer(Role::Fluid).connected || !peer(Role::Solid).connected) {
    if (app::interrupted()) throw coupling::CouplingError("coupler interrupted (SIGINT/SIGTERM)");
    if (now_s() > deadline) {
      std::vector<std::string> missing;
      for (Role r : kRoles)
        if (!peer(r).connected) missing.push_back(coupling::role_name(r));
      if (missing.size() == 1) blamed_ = missing[0];
      throw PeerLost(fmt::format("no Hello from the {} within {:g} s on {}", fmt::join(missing, " and "),
                                 opt_.connect_timeout, bound_));
    }
    beat_and_check();
    if (poll_once(50, in)) fail_peer(in.from, fmt::format("sent {} before the run started", coupling::body_name(in.e)));
  }
  handshake_done_ = true;
  if (transcript_)
    for (Role r : kRoles) {  // in role order, whatever the order of arrival
      transcript_->record("<-", r, peer(r).hello);
      transcript_->record("->", r, peer(r).welcome);
    }
}

void Hub::send(Role to, pb::Envelope& e) {
  cycle_ = e.header().cycle();
  time_ = e.header().time();
  beats_->set_clock(cycle_, time_);
  Peer& p = peer(to);
  std::string bytes = coupling::encode(e);
  p.bytes_sent += static_cast<double>(bytes.size());
  if (!sock_.send({p.id, std::move(bytes)}, 2000)) {
    blame(to);
    throw PeerLost(
        fmt::format("{} cannot be reached (connection closed) for {}", p.describe(to), coupling::body_name(e)));
  }
  if (transcript_) transcript_->record("->", to, e);
}

pb::Envelope Hub::next_from(Role from, const std::string& waiting_for) {
  auto& mine = inbox_[index(from)];
  if (!mine.empty()) {
    pb::Envelope e = std::move(mine.front());
    mine.pop_front();
    return e;
  }
  const double since = now_s();
  for (;;) {
    Incoming in = next_data(waiting_for, from, since);
    if (in.from == from) {
      Peer& p = peer(from);
      p.longest_answer = std::max(p.longest_answer, now_s() - since);
      return std::move(in.e);
    }
    auto& other = inbox_[index(in.from)];
    if (other.size() >= kMaxAhead)
      fail_peer(in.from,
                fmt::format("sent {} messages ahead of the cycle (last: {}) while the coupler waits for {} "
                            "from the {}",
                            other.size() + 1, coupling::body_name(in.e), waiting_for, coupling::role_name(from)));
    other.push_back(std::move(in.e));
  }
}

pb::Envelope Hub::expect(Role from, pb::Envelope::BodyCase kind, long cycle) {
  pb::Envelope e = next_from(from, coupling::body_name(kind));
  if (e.body_case() != kind)
    fail_peer(from, fmt::format("sent {} out of order: expected {} in cycle {}", coupling::body_name(e),
                                coupling::body_name(kind), cycle));
  if (e.header().cycle() != cycle)
    fail_peer(from, fmt::format("sent {} for cycle {}, expected cycle {}", coupling::body_name(kind),
                                e.header().cycle(), cycle));
  if (transcript_) transcript_->record("<-", from, e);
  return e;
}

std::array<pb::Envelope, 2> Hub::expect_both(pb::Envelope::BodyCase kind, long cycle) {
  // In role order; the one that comes later waits in its inbox meanwhile.
  return {expect(Role::Fluid, kind, cycle), expect(Role::Solid, kind, cycle)};
}

void Hub::stop_all(const std::string& reason, bool failure) noexcept {
  for (Role r : kRoles) {
    try {
      const Peer& p = peer(r);
      if (!p.connected) continue;
      pb::Envelope e = coupling::make_envelope(Role::Coupler, opt_.token, cycle_, time_);
      e.mutable_stop()->set_reason(reason);
      e.mutable_stop()->set_failure(failure);
      sock_.send({p.id, coupling::encode(e)}, 200);
      if (transcript_) transcript_->record("->", r, e);
    } catch (...) {}
  }
}

}  // namespace cosim::coupler
