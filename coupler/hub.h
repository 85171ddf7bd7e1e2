// The coupler's side of the connections: one ROUTER socket that both solvers' data and heartbeat connections
// reach. Handshake checks, heartbeats both ways, liveness (a peer silent for longer than the timeout is declared
// dead, naming it), typed receives that turn anything unexpected into an Error reply plus an exception.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "common/coupling/types.h"
#include "common/coupling/zmq_socket.h"
#include "coupler/heartbeat_service.h"
#include "coupler/stranger_limit.h"
#include "coupler/transcript.h"
#include "proto/coupling.pb.h"

namespace cosim::coupler {

struct HubOptions {
  std::string endpoint;  // to bind: ipc://path or tcp://host:port (port * = any)
  std::string token;
  std::string scene_hash;
  coupling::Mode mode = coupling::Mode::Impedance;
  coupling::Scheme scheme = coupling::Scheme::Pipelined;
  double timeout = 5.0;             // [s]
  double heartbeat_interval = 0.5;  // [s]
  double connect_timeout = 30.0;    // [s]
  // [s] the longest a peer may take to answer, heartbeats or not; 0: automatic, kAutoStepFactor times the
  // longest answer it has given so far, at least kAutoStepFloor.
  double step_timeout = 0.0;
  double max_message_bytes = 256.0 * 1024 * 1024;  // a larger message drops its connection unread
  long restarted_from = 0;  // cycle of the checkpoint set the run resumes from (both Hellos must say the same)
};
inline constexpr double kAutoStepFactor = 50.0, kAutoStepFloor = 120.0;

struct Peer {
  bool connected = false;
  std::string id;  // ROUTER routing id of its data connection (its heartbeats go to the HeartbeatService)
  std::string program;
  long pid = 0;
  std::uint32_t ranks = 1;  // MPI ranks it speaks for (Hello.ranks; its rank 0 holds the connection)
  std::vector<std::string> phase_names;
  std::vector<double> phase_min_pressure;        // [Pa] per phase (fluid, optional)
  double last_seen = 0;                          // steady clock [s]
  double busy = 0;                               // sum of Header.busy_seconds received [s]
  double output = 0;                             // of which Header.output_seconds (snapshots, checkpoints) [s]
  double longest_answer = 0;                     // the longest wait for one of its data messages [s]
  double bytes_received = 0, bytes_sent = 0;     // its data messages after the handshake, encoded envelopes [B]
  bool beats_on_data = false;                    // it sent a Heartbeat on the data connection (logged once)
  coupling::pb::Envelope hello, welcome;         // kept for the transcript
  std::string describe(coupling::Role r) const;  // "fluid (fluid_solver, pid 1234)"
};

class Hub {
 public:
  explicit Hub(const HubOptions& o, Transcript* transcript = nullptr);
  ~Hub();
  const std::string& bound_endpoint() const { return bound_; }
  const std::string& token() const { return opt_.token; }

  // Waits for a valid Hello from the fluid and the solid (refusing wrong ones with a reason); throws
  // coupling::Refused or PeerLost when the run cannot start.
  void handshake();
  // Sends to a peer; header filled by the hub (cycle, time).
  void send(coupling::Role to, coupling::pb::Envelope& e);
  // Next data message of `kind` from `from` for `cycle`; throws ProtocolError/PeerLost otherwise. Each peer's
  // messages are taken in the order it sent them; what the other peer sends meanwhile waits in its inbox (a
  // pipelined solid is a step ahead of the fluid).
  coupling::pb::Envelope expect(coupling::Role from, coupling::pb::Envelope::BodyCase kind, long cycle);
  // One message of `kind` from each solver (any order), returned as {fluid, solid}.
  std::array<coupling::pb::Envelope, 2> expect_both(coupling::pb::Envelope::BodyCase kind, long cycle);
  // Stop to every connected peer (best effort).
  void stop_all(const std::string& reason, bool failure) noexcept;

  const Peer& peer(coupling::Role r) const { return peers_[index(r)]; }
  Peer& peer(coupling::Role r) { return peers_[index(r)]; }
  double wait_seconds() const { return wait_; }  // time spent blocked in receives [s]
  // Replies Error to the peer and throws ProtocolError naming it.
  [[noreturn]] void reject(coupling::Role r, const std::string& what) { fail_peer(r, what); }
  // The role ("fluid", "solid") of the peer the last failure thrown here names (dead, refused, reported an error,
  // sent something wrong), "" when none: the launcher's cause of a failed run (coupler_summary.json "peer").
  const std::string& blamed() const { return blamed_; }

 private:
  static int index(coupling::Role r) { return r == coupling::Role::Fluid ? 0 : 1; }
  struct Incoming {
    coupling::Role from;
    coupling::pb::Envelope e;
  };
  // Blocks until a data message from a connected peer arrives (heartbeats and strangers handled inside).
  // Throws PeerLost when the peer `from`, waited for since `since`, has not answered within the step timeout.
  Incoming next_data(const std::string& waiting_for, coupling::Role from, double since);
  double step_limit(coupling::Role r) const;
  // The next message of one peer: its inbox first, else from the socket, queueing the other peer's.
  coupling::pb::Envelope next_from(coupling::Role from, const std::string& waiting_for);
  bool poll_once(int timeout_ms, Incoming& out);
  void beat_and_check();
  void reply_error(const std::string& id, const std::string& reason);
  std::string check_hello(const coupling::pb::Envelope& e) const;
  [[noreturn]] void fail_peer(coupling::Role r, const std::string& what);
  void blame(coupling::Role r) { blamed_ = coupling::role_name(r); }

  HubOptions opt_;
  Transcript* transcript_;
  coupling::ZmqContext ctx_;
  coupling::ZmqSocket sock_{ctx_, coupling::ZmqSocket::Type::Router};
  std::string bound_;
  std::unique_ptr<HeartbeatService> beats_;  // after sock_ and ctx_: its thread ends first
  std::array<Peer, 2> peers_;
  std::array<std::deque<coupling::pb::Envelope>, 2> inbox_;  // received, not yet expected
  double wait_ = 0;
  bool handshake_done_ = false;
  StrangerLimit strangers_;
  bool stranger_beat_said_ = false;  // a Heartbeat from a connection before its Hello was logged
  long cycle_ = 0;
  double time_ = 0;
  std::string blamed_;
};

}  // namespace cosim::coupler
