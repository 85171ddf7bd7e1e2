// The outputs of a run in its checkpoint: how far each snapshot series and each table had got, so that a restart
// continues them where the set was written (later snapshots and lines, of the run that stopped, are dropped).
#pragma once

#include <filesystem>
#include <string>

#include "common/checkpoint/part_file.h"
#include "common/io/line_log.h"
#include "common/io/snapshot_writer.h"

namespace cosim::checkpoint {

void put_series(PartWriter& w, const std::string& name, const io::SnapshotSeries& s);
// Continues `s` (a new, empty series) with the snapshots the part recorded under `name`.
void resume_series(const PartReader& r, const std::string& name, io::SnapshotSeries& s);

void put_log(PartWriter& w, const std::string& name, const io::LineLog& log);
// The table at `path` cut back to the length the part recorded under `name`, open for appending.
io::LineLog resume_log(const PartReader& r, const std::string& name, const std::filesystem::path& path);

}  // namespace cosim::checkpoint
