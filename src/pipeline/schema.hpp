#pragma once
// The JSON Schema (draft-07) of pipeline files, written from the reader's own key table
// (pipeline/detail/pipeline_keys.hpp): `terraweave schema` prints it, docs/pipeline.schema.json
// is its output (a test keeps the two equal), editors validate pipelines/*.yaml against it.
#include <string>

namespace tw {

// Pretty-printed (two spaces), ending in a newline.
std::string pipeline_schema_json();

}  // namespace tw
