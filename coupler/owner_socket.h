// The coupler's sockets are its user's alone: an ipc socket file takes the process's umask, so it is bound under
// umask 077 (a shared node's other users could otherwise connect under umask 000), and the file libzmq leaves
// behind when the socket closes is removed.
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "common/coupling/zmq_socket.h"

namespace cosim::coupler {

// Binds `endpoint` owner-only; returns the endpoint as bound (tcp: the port chosen).
inline std::string bind_owner_only(coupling::ZmqSocket& sock, const std::string& endpoint) {
  const mode_t old = ::umask(077);
  try {
    sock.bind(endpoint);
  } catch (...) {
    ::umask(old);
    throw;
  }
  ::umask(old);
  return sock.last_endpoint();
}

// Removes the socket file of an ipc endpoint that was bound (not an abstract one, ipc://@name).
inline void remove_socket_file(const std::string& bound) {
  if (bound.starts_with("ipc://") && bound.size() > 6 && bound[6] != '@') {
    std::error_code ignored;
    std::filesystem::remove(bound.substr(6), ignored);
  }
}

}  // namespace cosim::coupler
