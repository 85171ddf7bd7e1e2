// The coupling client both solvers use (no ZeroMQ or protobuf in the solvers). One Client per solver process.
//
//   coupling::ClientOptions o;  o.endpoint = ep;  o.token = tok;  o.role = Role::Solid;  o.scene_hash = h;
//   coupling::Client c(o);
//   for (;;) {
//     Directive d = c.next();                      // DtDecision, OutputRequest or Stop
//     if (d.kind == Directive::Kind::Stop) break;
//     if (d.kind == Directive::Kind::Output) { write snapshot d.output_index; continue; }
//     if (d.kind == Directive::Kind::Checkpoint) { write the state into d.directory; c.confirm_checkpoint(..);
//     continue; }
//     ... solver-specific cycle with one c.propose_dt(stable_dt) (docs/protocol.md "Writing a solver client":
//     where it goes depends on c.scheme() for the fluid) ...
//   }
//
// Every call blocks until the expected message arrives. While waiting, a background thread exchanges
// heartbeats with the coupler on a second connection; when the coupler is silent for longer than the
// timeout of its Welcome (default 5 s), the waiting call throws PeerLost naming the coupler. An unexpected,
// out-of-order or malformed message is answered with an Error and throws ProtocolError; a Stop with
// failure or an Error from the coupler throws RunStopped with the coupler's reason.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/coupling/errors.h"
#include "common/coupling/types.h"

namespace cosim::coupling {

struct ClientOptions {
  std::string endpoint;                    // ipc://... or tcp://host:port of the coupler
  std::string token;                       // per-run token (launcher: --token)
  Role role = Role::Fluid;                 // Fluid or Solid
  std::string scene_hash;                  // scene_hash(scene file, overrides)
  std::string program = "solver";          // for the coupler's messages
  std::vector<std::string> phase_names;    // fluid: its phases in sample order
  std::vector<double> phase_min_pressure;  // fluid: the lowest pressure each phase's EOS admits [Pa] (optional)
  std::uint32_t ranks = 1;                 // MPI ranks this connection speaks for (Hello.ranks; rank 0 connects)
  double connect_timeout = 30.0;           // [s] to wait for the Welcome
  std::uint32_t protocol_version = 0;      // 0: this build's; tests only set another
  // Checked while waiting for the coupler (every 0.1 s): true stops the wait with RunStopped (the solvers pass
  // their SIGINT/SIGTERM flag, so a signal ends a solver at once even while the coupler is silent).
  std::function<bool()> should_stop;
  // A restarted solver: the cycle of the checkpoint set it restored (Hello.restarted_from); it then expects the
  // DtDecision of cycle restarted_from + 1 first. 0: a fresh start.
  long restarted_from = 0;
  double restart_time = 0;  // [s] the set's time
};

class Client {
 public:
  // Connects and handshakes; throws Refused (with the coupler's reason) or PeerLost (no answer).
  explicit Client(const ClientOptions& opt);
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Waits for the coupler's next directive. A Stop without failure is returned; with failure it throws.
  Directive next();

  void send_faces(const Faces& faces);       // solid, once per cycle
  Faces receive_faces();                     // fluid, once per cycle
  void send_samples(const FluidSamples& s);  // fluid, once per cycle
  InterfaceStates receive_states();          // both, once per cycle
  void propose_dt(double dt);                // both, once per cycle [s]
  // Answers a Checkpoint directive: this solver's part `part` (a file name in the set directory) is written.
  void confirm_checkpoint(const std::string& part, std::uint64_t bytes);
  // Of the work since the last message, `seconds` went into writing outputs (a snapshot, a checkpoint part): sent
  // as Header.output_seconds with the next message, so that the coupler's timing keeps it apart from the solver's
  // steps (outputs of both solvers run at the same time; their steps do not in the sequential scheme).
  void add_output_seconds(double seconds);

  // Tells the coupler that this solver cannot go on (best effort, never throws).
  void report_error(const std::string& reason) noexcept;
  // Throws PeerLost when the coupler's heartbeats stopped (for solvers with long steps).
  void check() const;
  // Stops the heartbeats and closes the connections (the destructor does it too).
  void close() noexcept;

  Mode mode() const;
  Scheme scheme() const;   // where the fluid proposes its step (types.h)
  double timeout() const;  // [s]
  long cycle() const;      // current cycle (-1 before the first DtDecision)
  double time() const;     // t^n of the current cycle [s]

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosim::coupling
