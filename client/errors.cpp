// Status codes and the last error message of the C interface.
#include <stdexcept>

#include "client/handle.h"
#include "common/config/config.h"
#include "common/coupling/errors.h"

namespace cosim::client_detail {

namespace {
thread_local std::string last_error;
}

int fail(int code, const std::string& message) {
  last_error = message;
  return code;
}

int guarded(const std::function<void()>& f) {
  try {
    f();
    return COSIM_OK;
  } catch (const coupling::Refused& e) { return fail(COSIM_E_REFUSED, e.what()); } catch (const coupling::PeerLost& e) {
    return fail(COSIM_E_PEER_LOST, e.what());
  } catch (const coupling::ProtocolError& e) {
    return fail(COSIM_E_PROTOCOL, e.what());
  } catch (const coupling::RunStopped& e) {
    return fail(COSIM_E_STOPPED, e.what());
  } catch (const client_detail::Corrupt& e) {
    return fail(COSIM_E_CORRUPT, e.what());
  } catch (const config::ConfigError& e) { return fail(COSIM_E_SCENE, e.what()); } catch (const YAML::Exception& e) {
    return fail(COSIM_E_SCENE, e.what());
  } catch (const std::logic_error& e) {  // invalid_argument, out_of_range, a call out of order
    return fail(COSIM_E_ARGUMENT, e.what());
  } catch (const std::exception& e) { return fail(COSIM_E_FAILED, e.what()); } catch (...) {
    return fail(COSIM_E_FAILED, "unknown failure");
  }
}

coupling::Client& connected(const cosim_client* c) {
  if (!c) throw std::invalid_argument("null cosim_client handle");
  if (!c->client) throw std::logic_error("not connected: call cosim_hello() first");
  return *c->client;
}

int copy_out(const std::vector<double>& values, double* out, int capacity, int* length) {
  const int n = static_cast<int>(values.size());
  if (length) *length = n;
  if (n > capacity)
    return fail(COSIM_E_ARGUMENT,
                "output array holds " + std::to_string(capacity) + " values, " + std::to_string(n) + " needed");
  if (n > 0 && !out) return fail(COSIM_E_ARGUMENT, "null output array");
  std::copy(values.begin(), values.end(), out);
  return COSIM_OK;
}

}  // namespace cosim::client_detail

extern "C" const char* cosim_last_error(void) { return cosim::client_detail::last_error.c_str(); }
