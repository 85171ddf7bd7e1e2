#include "common/coupling/scene_hash.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <iterator>

#include "common/coupling/errors.h"

namespace cosim::coupling {

namespace {
void fnv1a(std::uint64_t& h, const std::string& s) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
}
}  // namespace

std::string scene_hash_of_text(const std::string& text, const std::vector<std::string>& overrides) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  fnv1a(h, text);
  for (const auto& o : overrides) fnv1a(h, "\n--set " + o);
  return fmt::format("{:016x}", h);
}

std::string scene_hash(const std::string& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CouplingError(fmt::format("{}: cannot read the scene file", file));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return scene_hash_of_text(text, overrides);
}

}  // namespace cosim::coupling
