// The scene hash all three processes compare in the handshake: FNV-1a 64 of the scene file's bytes followed
// by "\n--set " + each override, as 16 lower-case hex digits. cosim.client.scene_hash (python/cosim/client.py) computes
// the same.
#pragma once

#include <string>
#include <vector>

namespace cosim::coupling {

std::string scene_hash_of_text(const std::string& text, const std::vector<std::string>& overrides);
// Throws CouplingError naming the file when it cannot be read.
std::string scene_hash(const std::string& file, const std::vector<std::string>& overrides);

}  // namespace cosim::coupling
