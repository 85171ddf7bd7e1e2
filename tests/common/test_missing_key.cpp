// A required key that is missing while the section holds a typo of it: the message names the key that was given
// and where (its line, or the --set that gave it); a key that is valid in the section or too far from the missing
// one is not offered.
#include <gtest/gtest.h>

#include "common/config/config.h"

namespace cosim::config {
namespace {

// Reads mesh.cells (required) and mesh.lower (optional) of `text`, returns the error message ("" when none).
std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    Node root = load_string(text, "scene.yaml", sets);
    Node mesh = root.child("mesh");
    mesh.get_vector("lower", 1, 3, std::vector<double>{0.0});
    mesh.get_vector("cells", 1, 3);
    mesh.require<double>("end");
  } catch (const ConfigError& e) { return e.what(); }
  return "";
}

TEST(MissingKey, TheTypoThatWasGivenIsNamedWithItsLine) {
  const std::string e = error_of("mesh:\n  lower: [0]\n  end: 1\n  cell: [50]\n");
  EXPECT_NE(e.find("mesh.cells: expected a list of 1 to 3 numbers, but the key is missing (did you mean 'cell', "
                   "given at line 4?)"),
            std::string::npos)
      << e;
}

TEST(MissingKey, ATypoGivenOnTheCommandLineIsNamedWithItsSet) {
  const std::string e = error_of("mesh:\n  end: 1\n", {"mesh.cels=[50]"});
  EXPECT_NE(e.find("but the key is missing (did you mean 'cels', given with --set mesh.cels?)"), std::string::npos)
      << e;
}

TEST(MissingKey, ValidKeysAndDistantKeysAreNotOffered) {
  // 'lower' was read (a valid key), 'cfl' is three edits from 'end': neither is a typo of the missing key
  std::string e = error_of("mesh:\n  lower: [0]\n  cells: [5]\n  cfl: 1\n");
  EXPECT_NE(e.find("mesh.end: expected a value (a number), but the key is missing"), std::string::npos) << e;
  EXPECT_EQ(e.find("did you mean"), std::string::npos) << e;
  e = error_of("mesh:\n  lowr: [0]\n  cels: [5]\n");
  EXPECT_NE(e.find("(did you mean 'cels', given at line 3?)"), std::string::npos) << e;
  // a difference of case only is a typo however short the key
  e = error_of("mesh:\n  cells: [5]\n  END: 1\n");
  EXPECT_NE(e.find("(did you mean 'END', given at line 3?)"), std::string::npos) << e;
}

}  // namespace
}  // namespace cosim::config
