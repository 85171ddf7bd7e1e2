// The coupler's link for a solver on several ranks: rank 0 holds the one connection (Client) and hands every message
// it receives to the other ranks; what the solver sends leaves from rank 0 only (a solver gathers what it sends on
// rank 0 first: samples, faces). To the coupler a solver of many ranks is one peer of the same protocol.
// The ranks make every receiving call together; a failure on rank 0 (the coupler lost, a Stop with failure, a
// malformed message) reaches every rank as the same exception. On one rank the relay is the client itself.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "common/coupling/client.h"

namespace cosim::coupling {

class RankRelay {
 public:
  // Rank 0's text to every rank (every rank calls it together; what the others pass is ignored). Empty on one rank.
  using Share = std::function<std::string(const std::string&)>;
  // `client`: rank 0's connection (null on the other ranks, and on rank 0 when it could not connect: then every
  // rank's relay is not connected()). `share`: empty when the solver runs on one rank.
  RankRelay(std::unique_ptr<Client> client, Share share);
  bool connected() const { return connected_; }
  // Whether a receiving call threw what rank 0's threw (every rank threw it at the same call, so every rank may go
  // on to end the run together; a failure of one rank's own may leave the others waiting in an exchange).
  bool failed_together() const { return failed_together_; }

  Directive next();
  Faces receive_faces();
  InterfaceStates receive_states();
  // Rank 0 sends; the other ranks' calls do nothing.
  void send_faces(const Faces& faces);
  void send_samples(const FluidSamples& s);
  void propose_dt(double dt);
  void confirm_checkpoint(const std::string& part, std::uint64_t bytes);
  void add_output_seconds(double seconds);
  void report_error(const std::string& reason) noexcept;
  void close() noexcept;

  Mode mode() const { return mode_; }
  Scheme scheme() const { return scheme_; }
  double timeout() const { return timeout_; }
  long cycle() const { return cycle_; }
  // Seconds this rank spent encoding what rank 0 relays (rank 0) and decoding it (every rank): the relay's own work
  // besides moving the bytes (the share's).
  double codec_seconds() const { return codec_seconds_; }
  double time() const { return time_; }

 private:
  // Rank 0 runs `receive` and returns its message encoded; every rank returns what rank 0's call returned (or
  // throws what it threw).
  std::string relayed(const std::function<std::string()>& receive);
  bool root() const { return client_ != nullptr || !share_; }

  std::unique_ptr<Client> client_;
  Share share_;
  bool connected_ = false;
  bool failed_together_ = false;
  Mode mode_ = Mode::Robin;
  Scheme scheme_ = Scheme::Pipelined;
  double timeout_ = 0;
  long cycle_ = -1;
  double time_ = 0;
  double codec_seconds_ = 0;
};

}  // namespace cosim::coupling
