#include "coupler/transcript.h"

#include <fmt/format.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/text_format.h>

#include <cmath>
#include <cstdlib>

#include "common/coupling/errors.h"
#include "common/coupling/wire.h"

namespace cosim::coupler {

namespace {
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

// 6 significant digits; |v| < 1e-12 (round-off noise such as a transverse velocity of 1e-35 m/s) is 0.
double round6(double v) {
  if (!std::isfinite(v) || std::abs(v) < 1e-12) return std::isfinite(v) ? 0.0 : v;
  return std::strtod(fmt::format("{:.6g}", v).c_str(), nullptr);
}

void round_all(Message& m) {
  const auto* d = m.GetDescriptor();
  const auto* r = m.GetReflection();
  for (int i = 0; i < d->field_count(); ++i) {
    const FieldDescriptor* f = d->field(i);
    if (f->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
      if (f->is_repeated()) {
        for (int j = 0; j < r->FieldSize(m, f); ++j)
          r->SetRepeatedDouble(&m, f, j, round6(r->GetRepeatedDouble(m, f, j)));
      } else if (r->HasField(m, f)) {
        r->SetDouble(&m, f, round6(r->GetDouble(m, f)));
      }
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      if (f->is_repeated()) {
        for (int j = 0; j < r->FieldSize(m, f); ++j) round_all(*r->MutableRepeatedMessage(&m, f, j));
      } else if (r->HasField(m, f)) {
        round_all(*r->MutableMessage(&m, f));
      }
    }
  }
}
}  // namespace

std::string canonical_text(const coupling::pb::Envelope& e) {
  coupling::pb::Envelope c = e;
  auto* h = c.mutable_header();
  h->clear_busy_seconds();
  h->clear_output_seconds();
  if (!h->token().empty()) h->set_token("<token>");
  if (c.has_hello()) c.mutable_hello()->clear_pid();
  if (c.has_welcome() && !c.welcome().heartbeat_endpoint().empty())
    c.mutable_welcome()->set_heartbeat_endpoint("<heartbeat endpoint>");
  round_all(c);
  std::string text;
  google::protobuf::TextFormat::PrintToString(c, &text);
  return text;
}

Transcript::Transcript(const std::string& file) {
  if (file.empty()) return;
  out_.open(file);
  if (!out_) throw coupling::CouplingError(fmt::format("{}: cannot write the transcript", file));
  out_ << "# cosim coupling protocol transcript (coupler's view), protocol version " << coupling::kProtocolVersion
       << "\n";
}

void Transcript::record(const char* direction, coupling::Role peer, const coupling::pb::Envelope& e) {
  if (!out_.is_open()) return;
  out_ << "## coupler " << direction << " " << coupling::role_name(peer) << ": " << coupling::body_name(e) << "\n"
       << canonical_text(e);
  out_.flush();
}

}  // namespace cosim::coupler
