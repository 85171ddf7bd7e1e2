// Scene-file syntax the YAML parser accepts but a user did not mean: a key given twice is refused with both
// lines (yaml-cpp would keep the first, PyYAML the last); a syntax error caused by a tab says so.
#include <gtest/gtest.h>

#include "common/config/config.h"

namespace cosim::config {
namespace {

std::string error_of(const std::string& text) {
  try {
    load_string(text, "scene.yaml");
  } catch (const ConfigError& e) { return e.what(); }
  return "";
}

TEST(SceneSyntax, DuplicateKeysAreRefusedWithBothLines) {
  EXPECT_EQ(error_of("a: 1\nb: {c: 2}\n"), "");
  EXPECT_EQ(error_of("a: 1\nb: 2\na: 3\n"),
            "scene.yaml:3: key 'a' is given twice (first at line 1); give each key once");
  // nested, and inside a list element
  EXPECT_NE(error_of("f:\n  mesh: {cells: [4], cells: [5]}\n").find("scene.yaml:2: key 'cells' is given twice"),
            std::string::npos);
  EXPECT_NE(error_of("l:\n  - {x: 1}\n  - x: 1\n    y: 2\n    x: 3\n")
                .find("scene.yaml:5: key 'x' is given twice "
                      "(first at line 3)"),
            std::string::npos);
  EXPECT_EQ(error_of("l:\n  - {x: 1}\n  - {x: 2}\n"), "");  // the same key in two list elements is fine
}

TEST(SceneSyntax, ATabIsNamedAsTheCause) {
  const std::string e = error_of("a:\n\tb: 1\n");
  EXPECT_NE(e.find("scene.yaml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("the line contains a tab"), std::string::npos) << e;
  EXPECT_EQ(error_of("a:\n  b: 1\n"), "");
}

}  // namespace
}  // namespace cosim::config
