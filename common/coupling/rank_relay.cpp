#include "common/coupling/rank_relay.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <stdexcept>

#include "common/coupling/wire.h"
#include "proto/coupling.pb.h"

namespace cosim::coupling {

namespace {

// A relayed message: 'M' and the message, or 'E', the kind of the exception rank 0 caught, and its text.
constexpr char kMessage = 'M', kFailure = 'E';

std::string failure(char kind, const char* what) { return std::string{kFailure, kind} + what; }

[[noreturn]] void rethrow(const std::string& relayed) {
  const std::string what = relayed.substr(2);
  switch (relayed[1]) {
    case 'P': throw ProtocolError(what);
    case 'R': throw Refused(what);
    case 'L': throw PeerLost(what);
    case 'S': throw RunStopped(what);
    case 'C': throw CouplingError(what);
    case 'A': throw std::invalid_argument(what);
    default: throw std::runtime_error(what);
  }
}

std::string encode(const Directive& d) {
  const nlohmann::json j{
      {"kind", static_cast<int>(d.kind)}, {"cycle", d.cycle},   {"time", d.time},          {"dt", d.dt},
      {"output", d.output_index},         {"reason", d.reason}, {"directory", d.directory}};
  return j.dump();
}

Directive decode_directive(const std::string& s) {
  const nlohmann::json j = nlohmann::json::parse(s);
  Directive d;
  d.kind = static_cast<Directive::Kind>(j["kind"].get<int>());
  d.cycle = j["cycle"].get<long>();
  d.time = j["time"].get<double>();  // JSON keeps a double's every bit (shortest round trip)
  d.dt = j["dt"].get<double>();
  d.output_index = j["output"].get<int>();
  d.reason = j["reason"].get<std::string>();
  d.directory = j["directory"].get<std::string>();
  return d;
}

// Runs f, adding its seconds to `seconds`.
template <class F>
auto timed(double& seconds, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  auto out = f();
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

RankRelay::RankRelay(std::unique_ptr<Client> client, Share share)
    : client_(std::move(client)), share_(std::move(share)) {
  // What the Welcome said, from rank 0 to every rank.
  nlohmann::json welcome;
  if (client_)
    welcome = {{"mode", static_cast<int>(client_->mode())},
               {"scheme", static_cast<int>(client_->scheme())},
               {"timeout", client_->timeout()}};
  const std::string shared = share_ ? share_(welcome.dump()) : welcome.dump();
  const nlohmann::json w = nlohmann::json::parse(shared);
  connected_ = !w.is_null();
  if (!connected_) return;
  mode_ = static_cast<Mode>(w["mode"].get<int>());
  scheme_ = static_cast<Scheme>(w["scheme"].get<int>());
  timeout_ = w["timeout"].get<double>();
}

std::string RankRelay::relayed(const std::function<std::string()>& receive) {
  std::string out;
  if (client_) {
    try {
      out = kMessage + receive();
    } catch (const ProtocolError& e) { out = failure('P', e.what()); } catch (const Refused& e) {
      out = failure('R', e.what());
    } catch (const PeerLost& e) { out = failure('L', e.what()); } catch (const RunStopped& e) {
      out = failure('S', e.what());
    } catch (const CouplingError& e) { out = failure('C', e.what()); } catch (const std::invalid_argument& e) {
      out = failure('A', e.what());
    } catch (const std::exception& e) { out = failure('X', e.what()); }
  }
  if (share_) out = share_(out);
  if (out.empty()) throw std::logic_error("a relayed message without a connection on rank 0");
  if (out[0] == kFailure) {
    failed_together_ = true;
    rethrow(out);
  }
  return out.substr(1);
}

Directive RankRelay::next() {
  if (!share_) {
    const Directive d = client_->next();
    cycle_ = client_->cycle(), time_ = client_->time();
    return d;
  }
  const std::string text = relayed([&] {
    const Directive received = client_->next();
    return timed(codec_seconds_, [&] { return encode(received); });
  });
  const Directive d = timed(codec_seconds_, [&] { return decode_directive(text); });
  if (d.kind == Directive::Kind::Advance) cycle_ = d.cycle, time_ = d.time;
  return d;
}

Faces RankRelay::receive_faces() {
  if (!share_) return client_->receive_faces();
  pb::InterfaceFaces m;
  const std::string bytes = relayed([&] {
    const Faces received = client_->receive_faces();
    return timed(codec_seconds_, [&] {
      pb::InterfaceFaces f;
      to_pb(received, f);
      return f.SerializeAsString();
    });
  });
  return timed(codec_seconds_, [&] {
    if (!m.ParseFromString(bytes)) throw ProtocolError("the interface faces relayed from rank 0 cannot be read");
    return from_pb(m);
  });
}

InterfaceStates RankRelay::receive_states() {
  if (!share_) return client_->receive_states();
  pb::InterfaceStates m;
  const std::string bytes = relayed([&] {
    const InterfaceStates received = client_->receive_states();
    return timed(codec_seconds_, [&] {
      pb::InterfaceStates s;
      to_pb(received, s);
      return s.SerializeAsString();
    });
  });
  return timed(codec_seconds_, [&] {
    if (!m.ParseFromString(bytes)) throw ProtocolError("the interface states relayed from rank 0 cannot be read");
    return from_pb(m);
  });
}

void RankRelay::send_faces(const Faces& faces) {
  if (client_) client_->send_faces(faces);
}
void RankRelay::send_samples(const FluidSamples& s) {
  if (client_) client_->send_samples(s);
}
void RankRelay::propose_dt(double dt) {
  if (client_) client_->propose_dt(dt);
}
void RankRelay::confirm_checkpoint(const std::string& part, std::uint64_t bytes) {
  if (client_) client_->confirm_checkpoint(part, bytes);
}
void RankRelay::add_output_seconds(double seconds) {
  if (client_) client_->add_output_seconds(seconds);
}
void RankRelay::report_error(const std::string& reason) noexcept {
  if (client_) client_->report_error(reason);
}
void RankRelay::close() noexcept {
  if (client_) client_->close();
}

}  // namespace cosim::coupling
