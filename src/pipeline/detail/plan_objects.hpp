#pragma once
// The objects of a plan folder (pipeline/plan_io.hpp): files under objects/ named by the
// XXH3-128 of their bytes, and the {file, xxh3_128, bytes} entries of plan.json that name them.
// The plan's own fields and every method's entry (SynthesisMethod::encode) store through it.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/file_io.hpp"

namespace tw::detail {

class PlanObjects {
 public:
  explicit PlanObjects(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // Writes `bytes` once under their hash (an intact object of an earlier plan is kept) and
  // returns the entry naming it.
  nlohmann::json put(const std::string& bytes, const std::string& extension) const;
  nlohmann::json put_cbor(const nlohmann::json& value) const;
  // Values as bytes (plan_binary.hpp: to_bytes), behind a header of the magic "twplan.b" and
  // the plan version (uint32), as objects/<hash>.bin.
  nlohmann::json put_binary(std::string_view body) const;

  // What an entry names, refused (tw::Error naming `key`) when its bytes do not match their
  // hash or it is not under objects/.
  std::string get(const nlohmann::json& entry, const std::string& key) const;
  nlohmann::json get_cbor(const nlohmann::json& entry, const std::string& key) const;
  // A binary object's bytes, mapped (core/file_io.hpp: objects are written once, by rename);
  // body() is what follows the header (refused, naming `key`, when the header is not this
  // version's) and lives as long as the Binary.
  struct Binary {
    MappedFile file;
    std::string_view body() const;
  };
  Binary get_binary(const nlohmann::json& entry, const std::string& key) const;

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace tw::detail
