#include "pipeline/detail/exemplar_memo.hpp"

#include <charconv>

#include "core/file_hash.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

fs::path memo_path(const fs::path& dir, const ContentHash& hash) {
  return dir / "exemplars" / (hash.hex() + ".twc");
}

std::optional<int> positive(const std::string& text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value <= 0) return std::nullopt;
  return value;
}

}  // namespace

ContentHash exemplar_file_hash(const fs::path& path) {
  const fs::path height = path.parent_path() / (path.stem().string() + "_height.tif");
  return Hasher().file(path).file(height).digest();
}

std::optional<Exemplar> remembered_exemplar(const fs::path& dir, const ContentHash& hash,
                                            const fs::path& path) {
  const fs::path memo = memo_path(dir, hash);
  CacheRead read = read_cache_entry(memo);
  if (read.state != CacheRead::State::ok) return std::nullopt;
  const auto width = positive(read.sections["width"]);
  const auto height = positive(read.sections["height"]);
  const std::string& channels = read.sections["channels"];
  if (!width || !height || channels.empty()) return std::nullopt;
  Exemplar exemplar;
  exemplar.width = *width;
  exemplar.height = *height;
  for (std::size_t start = 0; start <= channels.size();) {
    const std::size_t end = std::min(channels.find('\n', start), channels.size());
    exemplar.channel_names.push_back(channels.substr(start, end - start));
    start = end + 1;
  }
  exemplar.path = path.string();
  touch_cache_entry(memo);  // used now: pruning by age keeps it
  return exemplar;
}

void remember_exemplar(CacheFolder& folder, const fs::path& dir, const ContentHash& hash,
                       const Exemplar& exemplar) {
  std::string channels;
  for (const std::string& name : exemplar.channel_names)
    channels += (channels.empty() ? "" : "\n") + name;
  folder.write(memo_path(dir, hash), {{"width", std::to_string(exemplar.width)},
                                      {"height", std::to_string(exemplar.height)},
                                      {"channels", channels}});
}

}  // namespace tw::detail
