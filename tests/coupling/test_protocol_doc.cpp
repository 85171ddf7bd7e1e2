// docs/protocol.md is what an outside solver author writes a client from: every message, field, enumeration and
// enumeration value of the wire format (taken from the compiled proto's descriptor, so nothing can be added to
// proto/coupling.proto without it) is named in the document.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "common/coupling/wire.h"
#include "coupling_test_util.h"
#include "proto/coupling.pb.h"

using namespace cosim::test;

TEST(ProtocolDocument, NamesEveryMessageFieldAndEnumValueOfTheProto) {
  const std::string doc = read_file(fs::path(COSIM_SOURCE_DIR) / "docs" / "protocol.md");
  ASSERT_FALSE(doc.empty());
  const google::protobuf::FileDescriptor* file = cosim::coupling::pb::Envelope::descriptor()->file();
  std::vector<std::string> names;
  for (int m = 0; m < file->message_type_count(); ++m) {
    const google::protobuf::Descriptor* d = file->message_type(m);
    names.push_back(d->name());
    for (int f = 0; f < d->field_count(); ++f) names.push_back(d->field(f)->name());
  }
  for (int e = 0; e < file->enum_type_count(); ++e) {
    const google::protobuf::EnumDescriptor* d = file->enum_type(e);
    names.push_back(d->name());
    for (int v = 0; v < d->value_count(); ++v) names.push_back(d->value(v)->name());
  }
  EXPECT_GT(names.size(), 80u);
  for (const std::string& n : names)
    EXPECT_TRUE(std::regex_search(doc, std::regex("\\b" + n + "\\b"))) << n << " is not in docs/protocol.md";
}

// The version the document describes is the one this build speaks: its title and both tables say it.
TEST(ProtocolDocument, StatesTheCurrentProtocolVersion) {
  const std::string doc = read_file(fs::path(COSIM_SOURCE_DIR) / "docs" / "protocol.md");
  const std::string v = std::to_string(cosim::coupling::kProtocolVersion);
  EXPECT_EQ(doc.rfind("# Coupling protocol (version " + v + ")\n", 0), 0u) << doc.substr(0, 80);
  EXPECT_NE(doc.find("`PROTOCOL_VERSION_CURRENT` (" + v + ") |"), std::string::npos);
  EXPECT_NE(doc.find("| `protocol_version` | uint32 | `PROTOCOL_VERSION_CURRENT` (" + v + ") of the sender |"),
            std::string::npos);
  EXPECT_EQ(std::regex_search(doc, std::regex("PROTOCOL_VERSION_CURRENT` \\((?!" + v + "\\))\\d+\\)")), false)
      << "docs/protocol.md names another current version";
}
