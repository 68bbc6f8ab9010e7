#pragma once
// All-or-nothing outputs. Every file of a run is first written under a temporary name in
// its final folder; commit() renames them all into place. A run that throws, or is killed,
// leaves the previous outputs untouched (and the destructor removes the temporaries).
#include <filesystem>
#include <string>
#include <vector>

namespace tw {

class OutputTransaction {
 public:
  OutputTransaction() = default;
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // The temporary path to write instead of `final_path` (same folder, same extension so
  // format drivers that look at the extension still work). Creates the folder.
  std::filesystem::path stage(const std::filesystem::path& final_path);
  // Renames every staged file into place.
  void commit();
  const std::vector<std::filesystem::path>& committed() const { return committed_; }

 private:
  struct Entry {
    std::filesystem::path temporary;
    std::filesystem::path final;
  };
  std::vector<Entry> staged_;
  std::vector<std::filesystem::path> committed_;
};

}  // namespace tw
