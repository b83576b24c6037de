#pragma once
// CSV of the runs, the ratio table of ours against the peers, a one-line human
// summary (with the per-phase profile) of each run, and the CSV of their timelines.
#include <ostream>
#include <vector>

#include "runner.h"

namespace bench {

void write_csv_header(std::ostream& out);
void write_csv_row(std::ostream& out, const RunRow& row);

// For each scene and sleeping mode that has ours at the default setting and a peer:
// peer time / our time, on the whole run and on the first and last windows.
void write_ratios(std::ostream& out, const std::vector<RunRow>& rows);

void write_summary(std::ostream& out, const RunRow& row);

// The runs' timelines (RunRow::timeline): one row per window of each run.
void write_timeline_header(std::ostream& out);
void write_timeline_rows(std::ostream& out, const RunRow& row);

}  // namespace bench
