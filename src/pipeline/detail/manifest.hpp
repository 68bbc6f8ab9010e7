#pragma once
// The run manifest's facts (report.json, docs/cli.md): hashes and sizes of what a run read
// and wrote, the range of heights, the time it started.
#include <map>
#include <string>
#include <vector>

#include "core/file_hash.hpp"
#include "core/grid.hpp"
#include "core/output_folder.hpp"
#include "pipeline/config.hpp"
#include "pipeline/run.hpp"

namespace tw::detail {

// Every input file of the pipeline once (a GeoPackage named by two classes is one entry), each
// followed by its companions that exist (InputFile::companions: an exemplar's NAME_height.tif). A
// URL (--allow-network) is listed without size or hash. `inputs`: the pipeline's
// (PipelineConfig::inputs).
std::vector<FileRecord> record_inputs(const std::vector<InputFile>& inputs);
// Every file staged so far (report.json is staged last, after this). `known`: digests already
// taken of staged files (by name under the folder; the tile cache hashes what it stores or
// reuses), which are not read again.
std::vector<FileRecord> record_outputs(
    const OutputFolder& output, const std::map<std::filesystem::path, FileDigest>& known = {});
HeightRange height_range(const Raster<float>& height);
std::string utc_timestamp();  // now, ISO 8601 in UTC to the second

}  // namespace tw::detail
