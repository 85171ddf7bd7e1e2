#include "common/coupling/client.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "common/coupling/endpoints.h"
#include "common/coupling/heartbeat.h"
#include "common/coupling/wire.h"
#include "common/coupling/zmq_socket.h"

namespace cosim::coupling {

namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

struct Client::Impl {
  ClientOptions opt;
  ZmqContext ctx;  // declared before the sockets: destroyed after them
  ZmqSocket data{ctx, ZmqSocket::Type::Dealer};
  std::unique_ptr<Heartbeat> heartbeat;
  Mode mode = Mode::Impedance;
  Scheme scheme = Scheme::Pipelined;
  double timeout = 5.0;
  long cycle = -1;
  double time = 0.0;
  double last_return = now_s();  // end of the previous protocol call: the solver works from here on
  double busy = 0;               // solver work since the previous send, up to last_return [s]
  double output = 0;             // of which writing outputs (add_output_seconds) [s]

  // Header.busy_seconds: the solver's work since its previous message, over all protocol calls in between.
  void send(pb::Envelope& e) {
    const double b = busy + (now_s() - last_return);
    e.mutable_header()->set_busy_seconds(b);
    e.mutable_header()->set_output_seconds(std::min(output, b));
    busy = 0;
    output = 0;
    if (!data.send({encode(e)}, 5000))
      throw PeerLost(
          fmt::format("{}: cannot send {} to the coupler at {}", role_name(opt.role), body_name(e), opt.endpoint));
    last_return = now_s();
  }

  pb::Envelope envelope() { return make_envelope(opt.role, opt.token, cycle, time); }

  // Replies Error to the coupler, then throws ProtocolError with the same text.
  [[noreturn]] void protocol_failure(const std::string& what) {
    pb::Envelope e = envelope();
    e.mutable_error()->set_reason(what);
    data.send({encode(e)}, 200);
    throw ProtocolError(fmt::format("{}: {}", role_name(opt.role), what));
  }

  // Waits for the next message on the data connection; throws PeerLost when the heartbeats say the coupler
  // is dead or (before the heartbeats run) after max_wait seconds.
  pb::Envelope receive(const std::string& expected, double max_wait) {
    const double start = now_s();
    busy += start - last_return;
    Frames frames;
    while (!data.receive(frames, 100)) {
      if (opt.should_stop && opt.should_stop())
        throw RunStopped(
            fmt::format("{}: interrupted while waiting for {} from the coupler", role_name(opt.role), expected));
      if (heartbeat && heartbeat->lost()) throw PeerLost(heartbeat->lost_message());
      if (max_wait > 0 && now_s() - start > max_wait)
        throw PeerLost(fmt::format("{}: no {} from the coupler at {} within {:g} s", role_name(opt.role), expected,
                                   opt.endpoint, max_wait));
    }
    if (frames.size() != 1) protocol_failure(fmt::format("malformed message: {} frames, expected 1", frames.size()));
    std::string why;
    auto e = decode(frames[0], why);
    if (!e) protocol_failure(why);
    const auto& h = e->header();
    if (h.protocol_version() != kProtocolVersion && !e->has_welcome())
      protocol_failure(fmt::format("{} from the coupler has protocol version {}, this client speaks {}", body_name(*e),
                                   h.protocol_version(), kProtocolVersion));
    if (h.token() != opt.token) protocol_failure(fmt::format("{} with a wrong run token", body_name(*e)));
    if (e->has_error()) throw RunStopped(fmt::format("coupler reported an error: {}", e->error().reason()));
    const std::string problem = validate(*e);
    if (!problem.empty()) protocol_failure(problem);
    return *e;
  }

  // Receives a message of one expected kind belonging to the current cycle.
  pb::Envelope expect(pb::Envelope::BodyCase kind, const std::string& name) {
    pb::Envelope e = receive(name, 0.0);
    if (e.has_stop())
      throw RunStopped(fmt::format("coupler stopped the run while {} waited for {}: {}", role_name(opt.role), name,
                                   e.stop().reason()));
    if (e.body_case() != kind)
      protocol_failure(
          fmt::format("expected {} in cycle {}, got {} (cycle {})", name, cycle, body_name(e), e.header().cycle()));
    if (e.header().cycle() != cycle)
      protocol_failure(fmt::format("{} for cycle {}, expected cycle {}", name, e.header().cycle(), cycle));
    last_return = now_s();
    return e;
  }

  void handshake() {
    pb::Envelope e = envelope();
    if (opt.protocol_version) e.mutable_header()->set_protocol_version(opt.protocol_version);
    auto* hello = e.mutable_hello();
    hello->set_role(to_pb(opt.role));
    hello->set_scene_hash(opt.scene_hash);
    hello->set_program(opt.program);
    hello->set_pid(static_cast<long>(::getpid()));
    for (const auto& p : opt.phase_names) hello->add_phase_names(p);
    for (double p : opt.phase_min_pressure) hello->add_phase_min_pressure(p);
    hello->set_restarted_from(opt.restarted_from);
    hello->set_ranks(opt.ranks);
    data.send({encode(e)}, 5000);
    pb::Envelope w = receive("Welcome", opt.connect_timeout);
    if (!w.has_welcome()) protocol_failure(fmt::format("expected Welcome, got {}", body_name(w)));
    if (!w.welcome().accepted())
      throw Refused(
          fmt::format("coupler at {} refused {}: {}", opt.endpoint, role_name(opt.role), w.welcome().reason()));
    mode = from_pb(w.welcome().mode());
    scheme = from_pb(w.welcome().scheme());
    timeout = w.welcome().timeout() > 0 ? w.welcome().timeout() : 5.0;
    const double interval = w.welcome().heartbeat_interval() > 0 ? w.welcome().heartbeat_interval() : 1.0;
    heartbeat =
        std::make_unique<Heartbeat>(ctx, heartbeat_connect_endpoint(w.welcome().heartbeat_endpoint(), opt.endpoint),
                                    opt.role, opt.token, interval, timeout);
    last_return = now_s();
  }
};

Client::Client(const ClientOptions& opt) : impl_(std::make_unique<Impl>()) {
  if (opt.role == Role::Coupler) throw CouplingError("ClientOptions.role: expected fluid or solid");
  impl_->opt = opt;
  if (opt.restarted_from > 0) {  // the next DtDecision is the first after the set's cycle
    impl_->cycle = opt.restarted_from;
    impl_->time = opt.restart_time;
  }
  impl_->data.connect(opt.endpoint);
  impl_->handshake();
}

Client::~Client() { close(); }

Directive Client::next() {
  Impl& m = *impl_;
  pb::Envelope e = m.receive("DtDecision, OutputRequest or Stop", 0.0);
  m.last_return = now_s();
  Directive d;
  const auto& h = e.header();
  if (e.has_stop()) {
    if (e.stop().failure()) throw RunStopped(fmt::format("coupler stopped the run: {}", e.stop().reason()));
    d.kind = Directive::Kind::Stop;
    d.reason = e.stop().reason();
  } else if (e.has_dt_decision()) {
    if (h.cycle() != m.cycle + 1)
      m.protocol_failure(fmt::format("DtDecision for cycle {}, expected cycle {}", h.cycle(), m.cycle + 1));
    m.cycle = h.cycle();
    m.time = h.time();
    d.kind = Directive::Kind::Advance;
    d.dt = e.dt_decision().dt();
  } else if (e.has_output_request()) {
    if (h.cycle() != m.cycle)
      m.protocol_failure(fmt::format("OutputRequest for cycle {}, expected cycle {}", h.cycle(), m.cycle));
    d.kind = Directive::Kind::Output;
    d.output_index = static_cast<int>(e.output_request().index());
  } else if (e.has_checkpoint_request()) {
    if (h.cycle() != m.cycle)
      m.protocol_failure(fmt::format("CheckpointRequest for cycle {}, expected cycle {}", h.cycle(), m.cycle));
    d.kind = Directive::Kind::Checkpoint;
    d.directory = e.checkpoint_request().directory();
  } else {
    m.protocol_failure(fmt::format(
        "expected DtDecision, OutputRequest, CheckpointRequest or Stop after cycle {}, got {}", m.cycle, body_name(e)));
  }
  d.cycle = h.cycle();
  d.time = h.time();
  return d;
}

void Client::send_faces(const Faces& faces) {
  pb::Envelope e = impl_->envelope();
  to_pb(faces, *e.mutable_faces());
  const std::string problem = validate(e);
  if (!problem.empty()) throw ProtocolError("solid: cannot send " + problem);
  impl_->send(e);
}

Faces Client::receive_faces() { return from_pb(impl_->expect(pb::Envelope::kFaces, "InterfaceFaces").faces()); }

void Client::send_samples(const FluidSamples& s) {
  pb::Envelope e = impl_->envelope();
  to_pb(s, *e.mutable_samples());
  const std::string problem = validate(e);
  if (!problem.empty()) throw ProtocolError("fluid: cannot send " + problem);
  impl_->send(e);
}

InterfaceStates Client::receive_states() {
  return from_pb(impl_->expect(pb::Envelope::kStates, "InterfaceStates").states());
}

void Client::propose_dt(double dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw ProtocolError(
        fmt::format("{}: DtProposal.dt: {}, expected a finite number > 0", role_name(impl_->opt.role), dt));
  pb::Envelope e = impl_->envelope();
  e.mutable_dt_proposal()->set_dt(dt);
  impl_->send(e);
}

void Client::confirm_checkpoint(const std::string& part, std::uint64_t bytes) {
  pb::Envelope e = impl_->envelope();
  e.mutable_checkpoint_written()->set_part(part);
  e.mutable_checkpoint_written()->set_bytes(bytes);
  impl_->send(e);
}

void Client::add_output_seconds(double seconds) {
  if (seconds > 0) impl_->output += seconds;
}

void Client::report_error(const std::string& reason) noexcept {
  try {
    pb::Envelope e = impl_->envelope();
    e.mutable_error()->set_reason(reason);
    impl_->data.send({encode(e)}, 500);
  } catch (...) {}
}

void Client::check() const {
  if (impl_->heartbeat && impl_->heartbeat->lost()) throw PeerLost(impl_->heartbeat->lost_message());
}

void Client::close() noexcept {
  if (!impl_) return;
  if (impl_->heartbeat) impl_->heartbeat->stop();
  impl_->heartbeat.reset();
  try {
    impl_->data.set_linger(500);  // let a last Error or DtProposal leave
  } catch (...) {}
}

Mode Client::mode() const { return impl_->mode; }
Scheme Client::scheme() const { return impl_->scheme; }
double Client::timeout() const { return impl_->timeout; }
long Client::cycle() const { return impl_->cycle; }
double Client::time() const { return impl_->time; }

}  // namespace cosim::coupling
