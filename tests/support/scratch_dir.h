// Scratch paths for tests that write files: everything goes under one directory per test process,
// <tmp>/cosim_test_<pid>, which is removed when the program exits without a failed test (kept for a look
// otherwise). Tests no longer leave a directory per run in /tmp.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace cosim::test {

inline const std::filesystem::path& scratch_root() {
  struct Root {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("cosim_test_" + std::to_string(::getpid()));
    ~Root() {
      const ::testing::UnitTest* ut = ::testing::UnitTest::GetInstance();
      if (ut && ut->Failed()) return;
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Root root;
  return root.path;
}

// <root>/<name>, with the root created and nothing at <name> (an earlier test's files removed).
inline std::filesystem::path scratch_path(const std::string& name) {
  std::filesystem::create_directories(scratch_root());
  const std::filesystem::path p = scratch_root() / name;
  std::error_code ignored;
  std::filesystem::remove_all(p, ignored);
  return p;
}

}  // namespace cosim::test
