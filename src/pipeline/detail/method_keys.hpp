#pragma once
// A synthesis method's part of the one key table (detail/pipeline_keys.hpp, docs/methods.md,
// "Its keys"): the blocks it owns and the keys it adds to the file's top level or to a line
// class, described next to its glue (methods/<name>/<name>_keys.cpp), so the table names none of
// them. The reader's MapReaders and `terraweave schema` see the table with them in place.
#include <string_view>
#include <vector>

#include "pipeline/detail/pipeline_keys.hpp"

namespace tw::detail {

// A key the method adds to a block of the table: root or line_class.
struct PlacedKey {
  std::string_view block{};
  std::string_view after{};  // the key it follows in that block (the schema's order)
  KeySpec key{};
};

struct MethodKeys {
  std::vector<PlacedKey> keys{};
  std::vector<KeyBlock> blocks{};  // its own blocks, after the table's own but `existing`
};

// The built-in methods' keys in the schema's order, which docs/pipeline.schema.json's bytes
// follow (synthesis_method.cpp, beside the methods' registration): patterns, grown, network,
// areas.
const std::vector<MethodKeys>& builtin_method_keys();

}  // namespace tw::detail
