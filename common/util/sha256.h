// SHA-256 (FIPS 180-4) of a byte stream or a file, as `sha256sum` prints it: the checksums of checkpoint parts.
//   Sha256 h;  h.update(bytes);  std::string hex = h.hex_digest();
//   std::string hex = sha256_of_file(path);   // std::runtime_error naming the file when it cannot be read
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace cosim::util {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const std::uint8_t> bytes);
  // The digest as 64 lower-case hex digits; the object is finished afterwards (a further update is an error).
  std::string hex_digest();

 private:
  void compress(const std::uint8_t* block);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  // bytes so far
  bool finished_ = false;
};

struct FileDigest {
  std::uint64_t bytes = 0;
  std::string sha256;
};

FileDigest sha256_of_file(const std::filesystem::path& file);

}  // namespace cosim::util
