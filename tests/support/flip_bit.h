// Damages a file as a bad sector or a stray write would, for the tests that a corrupt file is refused.
#pragma once

#include <filesystem>
#include <fstream>

namespace cosim::test {

// Flips one bit of `file` at byte `at` (counted from the end when negative).
inline void flip_bit(const std::filesystem::path& file, long at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(0, std::ios::end);
  const long size = f.tellg();
  const long pos = at >= 0 ? at : size + at;
  f.seekg(pos);
  char c = 0;
  f.read(&c, 1);
  c ^= 0x10;
  f.seekp(pos);
  f.write(&c, 1);
}

}  // namespace cosim::test
