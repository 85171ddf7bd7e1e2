// Envelope encoding, header checks, array-size validation and conversions between the plain structs of
// types.h and the generated protobuf messages. Shared by the client library and the coupler.
#pragma once

#include <optional>
#include <string>

#include "common/coupling/types.h"
#include "proto/coupling.pb.h"

namespace cosim::coupling {

constexpr std::uint32_t kProtocolVersion = pb::PROTOCOL_VERSION_CURRENT;
// Hello.ranks above this is refused: no solver speaks for more MPI ranks (a larger value is a wrong field).
constexpr std::uint32_t kMaxHelloRanks = 1000000;
// Hello.ranks as the peer meant it: 0 (not sent) is one rank.
inline std::uint32_t hello_ranks(const pb::Hello& h) { return h.ranks() == 0 ? 1u : h.ranks(); }

pb::Role to_pb(Role r);
Role from_pb(pb::Role r);  // ROLE_UNSPECIFIED -> Coupler is never produced: throws ProtocolError
pb::CouplingMode to_pb(Mode m);
Mode from_pb(pb::CouplingMode m);
pb::CouplingScheme to_pb(Scheme s);
Scheme from_pb(pb::CouplingScheme s);  // UNSPECIFIED -> Pipelined

// "InterfaceFaces", "Hello", ..., or "(empty)" when no body is set.
std::string body_name(const pb::Envelope& e);
std::string body_name(pb::Envelope::BodyCase c);

// Envelope with a filled header.
pb::Envelope make_envelope(Role sender, const std::string& token, long cycle, double time, double busy = 0.0);

std::string encode(const pb::Envelope& e);
// Parses bytes; nullopt and a reason when they are not an Envelope with a header and a body.
std::optional<pb::Envelope> decode(const std::string& bytes, std::string& why);

// Array sizes and values of a body: empty string when consistent, otherwise "InterfaceFaces.normal: 6 values,
// expected dim * count = 9". Non-finite values are rejected where the protocol forbids them.
std::string validate(const pb::Envelope& e);
// The samples' pressures against the lowest pressure each phase admits (Hello.phase_min_pressure; empty: no
// check), on wetted faces: "" or the field, face, phase and value.
std::string validate_sample_pressures(const pb::FluidSamples& m, const std::vector<double>& min_pressure,
                                      const std::vector<std::string>& phase_names);

void to_pb(const Faces& f, pb::InterfaceFaces& m);
Faces from_pb(const pb::InterfaceFaces& m);
void to_pb(const FluidSamples& s, pb::FluidSamples& m);
FluidSamples from_pb(const pb::FluidSamples& m);
void to_pb(const InterfaceStates& s, pb::InterfaceStates& m);
InterfaceStates from_pb(const pb::InterfaceStates& m);

}  // namespace cosim::coupling
