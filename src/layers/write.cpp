#include "layers/write.hpp"

#include "core/log.hpp"

namespace tw {

std::vector<std::filesystem::path> write_layer_set(const LayerSet& set,
                                                   const std::filesystem::path& dir,
                                                   OutputStager& tx, const WriteOptions& options) {
  validate_layer_set(set);
  std::vector<std::filesystem::path> written;
  for (const auto& layer : set.layers) {
    if (options.exr) {
      const auto final_path = dir / (layer.name + ".exr");
      write_exr(set, layer, tx.stage(final_path), options.exr_compression, options.exr_zip_level,
                options.exr_pixels);
      written.push_back(final_path);
    }
    if (options.geotiff) {
      const auto final_path = dir / (layer.name + ".tif");
      write_geotiff(set, layer, tx.stage(final_path), options.geotiff_options);
      written.push_back(final_path);
    }
    logger().debug("layer '{}' written ({} channels)", layer.name, layer.channels.size());
  }
  if (options.preview) {
    const auto final_path = dir / "preview.png";
    write_preview_png(set, tx.stage(final_path), options.preview_lines, options.preview_max_size);
    written.push_back(final_path);
  }
  return written;
}

}  // namespace tw
