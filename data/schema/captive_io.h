// Reading and writing captive campaigns: the HDF5 layout (one file per
// campaign, one group per run) and the CSV layout for towing-tank data (one
// file per run). Both are specified in data/schema/captive_schema.md.
#pragma once

#include <filesystem>
#include <istream>

#include "data/schema/captive_run.h"

namespace kelvin::data {

inline constexpr std::string_view kCaptiveSchema = "kelvin.captive/1";

class H5Writer;

// Writes the campaign atomically (temporary file + rename).
void WriteCampaignH5(const CaptiveCampaign& campaign, const std::filesystem::path& path);
// Writes the campaign into `w` and leaves the Commit() to the caller, who
// adds its own attributes and datasets first: the file then appears under
// its name with all of them at once.
void WriteCampaignH5(const CaptiveCampaign& campaign, H5Writer& w);

// Reads and validates (ValidateCampaign) a campaign. Throws
// kelvin::DataFileError naming the file, the run and the channel for a
// missing channel, units other than s / N / N m, unknown motion kinds and
// everything ValidateCampaign rejects.
CaptiveCampaign ReadCampaignH5(const std::filesystem::path& path);

// One run as CSV: '# key: value' header lines, then a header row
// 'time [s],X [N],Y [N],N [N m]' and one row per sample.
void WriteRunCsv(const CaptiveRun& run, const std::filesystem::path& path);
// Reads one run; the run is named by its '# run:' line or the file stem.
// Throws kelvin::DataFileError with the file, line, run and channel.
CaptiveRun ReadRunCsv(const std::filesystem::path& path);
// The same from a stream; `path` names the run and the file in messages.
CaptiveRun ReadRunCsv(std::istream& in, const std::filesystem::path& path);

}  // namespace kelvin::data
