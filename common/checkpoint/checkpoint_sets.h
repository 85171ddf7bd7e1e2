// The checkpoint sets of a run and when to write one.
//
// Layout: ROOT/NNNNNNNNN/ (ROOT is normally RUN_DIR/checkpoints; NNNNNNNNN the coupled cycle, or the standalone
// fluid's step, the set holds) with one part per process (fluid.h5, solid.h5, coupler.h5: part_file.h) and
// manifest.json, written last and atomically by the process that drives the time once every part is in. The
// manifest records each part's size and SHA-256 (from the digest file its writer left beside it, part_file.h) and
// the cycle and time of the set, which every part must hold too. A set without a manifest, or one whose manifest
// names a part that is missing, is incomplete: a restart never uses it and prune() removes it once a later set is
// complete. A set whose parts do not match their manifest (a flipped bit, a truncated or replaced file, an edited
// manifest) is corrupt: verify_set() refuses it by name, and a restart takes the newest set that verifies.
//
// Scene keys (coupling.checkpoint in a coupled run, fluid.checkpoint in a fluid-only one):
//   checkpoint: {interval: 1.0e-3, cycles: 500, keep: 2}   # [s] of simulated time, [-] cycles; either or both
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/checkpoint/part_file.h"
#include "common/config/config.h"

namespace cosim::checkpoint {

inline constexpr const char* kManifestName = "manifest.json";
inline constexpr const char* kSetFormat = "cosim-checkpoint-set-2";

struct CheckpointPolicy {
  double interval = 0;  // [s] of simulated time between sets; 0: none by time
  long cycles = 0;      // cycles (steps) between sets; 0: none by count
  int keep = 2;         // complete sets kept (the newest)
  bool enabled() const { return interval > 0 || cycles > 0; }
  // A set is due after the cycle that took the time from t_prev to t when it crossed a multiple of the interval,
  // or when the cycle count is a multiple of `cycles`.
  bool due(long cycle, double t_prev, double t) const;
};

// "checkpoints every 0.001 s, keep 2" / "no checkpoints", for the plan cosim check prints.
std::string describe(const CheckpointPolicy& p);

// Reads interval, cycles and keep from `section` (null: checkpoints off) and finishes it.
CheckpointPolicy read_checkpoint_policy(config::Node* section);

std::filesystem::path set_path(const std::filesystem::path& root, long cycle);

// Makes the (empty) directory of set `cycle` under root, absolute: an incomplete set of that cycle, left by a run
// that stopped while writing it, is removed first. Throws std::runtime_error naming the directory.
std::filesystem::path prepare_set(const std::filesystem::path& root, long cycle);

// What a manifest records of the scene: its text (the file as read), the --set overrides, the program's version.
nlohmann::json scene_record(const std::string& scene_file, const std::vector<std::string>& overrides);

struct SetInfo {
  long cycle = 0;
  double time = 0;
  std::filesystem::path dir;
  nlohmann::json manifest;
};

// Writes DIR/manifest.json atomically: `m` with format, cycle, time and the parts' checksums added. m["parts"]
// lists the part files; each must exist in `dir` (std::runtime_error naming the missing one otherwise: the set
// stays incomplete). A part's size and SHA-256 come from its digest file, or from the part itself without one.
void write_manifest(const std::filesystem::path& dir, long cycle, double time, nlohmann::json m);

// The complete sets under root, oldest first (a missing root: none). Complete: a manifest naming parts that are
// all there; their contents are not read (verify_set does that).
std::vector<SetInfo> complete_sets(const std::filesystem::path& root);

// Checks one part of set `s` against the manifest: the size and SHA-256 it records, and the cycle the part holds
// (its "cycle" entry) against the manifest's. Throws std::runtime_error naming the file and what differs.
void verify_part(const SetInfo& s, const std::string& part);
// verify_part for every part of the set.
void verify_set(const SetInfo& s);

// The part `file` of the set in `dir` open for reading as a part of `kind`, once the manifest and verify_part
// have accepted it: what a restarting process reads. Throws std::runtime_error naming the set and the cause.
PartReader open_verified_part(const std::filesystem::path& dir, const std::string& file, std::string_view kind);

struct SetChoice {
  SetInfo set;
  std::vector<std::string> skipped;  // newer sets passed over, each "DIR: why", newest first
};
// The set a restart uses: `cycle` when given (which must be complete and verify), else the newest set that is
// complete and verifies, with the newer ones it passed over and why. Throws std::runtime_error saying what is
// there (and what was wrong with each) when there is none.
SetChoice choose_set(const std::filesystem::path& root, std::optional<long> cycle = std::nullopt);
// choose_set(root, cycle).set.
SetInfo find_set(const std::filesystem::path& root, std::optional<long> cycle = std::nullopt);

// Reads and checks one set's manifest: its format, its cycle against the directory's name, every part present
// with a checksum (std::runtime_error naming the file when it is not a complete set).
SetInfo read_set(const std::filesystem::path& dir);

// Removes every set under root (the numbered directories only): a fresh run into a directory starts with none, so
// that no set of an earlier run is kept as newer than its own or restarted from later.
void clear(const std::filesystem::path& root);

// Keeps the newest `keep` complete sets and removes the older ones and every incomplete set older than the newest
// complete one (best effort: errors are ignored, a restart only ever uses complete sets).
void prune(const std::filesystem::path& root, int keep);

}  // namespace cosim::checkpoint
