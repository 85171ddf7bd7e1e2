// Protocol transcript: every message the coupler sends or receives, in protobuf text format, numbers rounded to
// 6 significant digits and run-dependent fields (token, pid, busy_seconds) blanked, so that a transcript of a
// deterministic run is reproducible and any change to the wire format shows as a diff.
#pragma once

#include <fstream>
#include <string>

#include "common/coupling/types.h"
#include "proto/coupling.pb.h"

namespace cosim::coupler {

// The canonical text of one message (also used by the tests).
std::string canonical_text(const coupling::pb::Envelope& e);

class Transcript {
 public:
  Transcript() = default;
  explicit Transcript(const std::string& file);  // empty: disabled
  // direction "->" (coupler to peer) or "<-" (peer to coupler)
  void record(const char* direction, coupling::Role peer, const coupling::pb::Envelope& e);

 private:
  std::ofstream out_;
};

}  // namespace cosim::coupler
