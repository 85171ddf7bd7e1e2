// Exceptions of the coupling library. All derive from CouplingError (a std::runtime_error) and carry a
// message that names the peer, the message and the field concerned.
#pragma once

#include <stdexcept>

namespace cosim::coupling {

class CouplingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A malformed, unexpected or out-of-order message (an Error reply has been sent when possible).
class ProtocolError : public CouplingError {
 public:
  using CouplingError::CouplingError;
};

// The handshake was refused (version, scene hash, token, role).
class Refused : public CouplingError {
 public:
  using CouplingError::CouplingError;
};

// A peer stopped answering (no message or heartbeat for longer than the timeout), or reported an error.
class PeerLost : public CouplingError {
 public:
  using CouplingError::CouplingError;
};

// The coupler ended the run (Stop with failure = true); the message is the coupler's reason.
class RunStopped : public CouplingError {
 public:
  using CouplingError::CouplingError;
};

}  // namespace cosim::coupling
