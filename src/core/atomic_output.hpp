#pragma once
// All-or-nothing outputs of loose files (`synth -o x.png`, tests, benchmarks). Every file is
// first written under a temporary name in its final folder; commit() renames them one by one,
// so each file is old or new, never half-written. A pipeline's output folder, whose files must
// change together, is an OutputFolder (core/output_folder.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "core/staging_registry.hpp"

namespace tw {

// What a writer needs: where to write instead of the final path.
class OutputStager {
 public:
  virtual ~OutputStager() = default;
  virtual std::filesystem::path stage(const std::filesystem::path& final_path) = 0;
};

class OutputTransaction final : public OutputStager {
 public:
  OutputTransaction() = default;
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // The temporary path to write instead of `final_path` (same folder, same extension so
  // format drivers that look at the extension still work). Creates the folder.
  std::filesystem::path stage(const std::filesystem::path& final_path) override;
  // Renames every staged file into place.
  void commit();
  const std::vector<std::filesystem::path>& committed() const { return committed_; }

 private:
  struct Entry {
    StagedPath temporary;  // removed with the transaction unless committed
    std::filesystem::path final;
  };
  std::vector<Entry> staged_;
  std::vector<std::filesystem::path> committed_;
};

}  // namespace tw
