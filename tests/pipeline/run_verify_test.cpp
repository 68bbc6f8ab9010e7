// The commands that read a finished run (`diff`, `export`, `view`) check its files against
// report.json's hashes first (issue #24 item 4, pipeline/run_layers.hpp verify_run_files): a
// truncated height.tif was "identical" to diff, 64 flipped bytes gave an export heights of
// 2.25e35 m. Each case through the real CLI: one error naming the file and what to do, nothing
// written; `--no-verify` reads the files as they are.
#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "test_support.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class RunVerify : public ::testing::Test {
 protected:
  // Two runs of one pipeline, made once; each test changes copies of them.
  static void SetUpTestSuite() {
    runs = new TempDir;
    std::ofstream(*runs / "pipeline.yaml") << R"(version: 1
seed: 3
generate: { width: 48, height: 40, pixel_size: 10, relief: 40, origin: [500000, 5000000] }
output: { preview: false, exr: false, compress: none }
features:
  ridges: { source: )" << (source_dir() / "samples/map.gpkg").string()
                                           << R"(, layer: ridges, kind: ridge, width: 20 }
)";
    for (const char* out : {"run", "other"})
      run_command("cd '" + runs->path().string() + "' && '" + terraweave_binary().string() +
                  "' -q run pipeline.yaml --out " + out);
  }
  static void TearDownTestSuite() { delete runs; }
  void SetUp() override {
    for (const char* out : {"run", "other"}) {
      ASSERT_TRUE(fs::exists(*runs / out / "report.json")) << out;
      fs::copy(*runs / out, dir / out, fs::copy_options::recursive);
    }
  }
  CommandResult terraweave(const std::string& args) const {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args + " 2>&1");
  }
  // The refusal: exit `code`, one error line naming the file, report.json and what to do.
  void expect_refused(const std::string& args, int code, const std::string& file) const {
    const CommandResult r = terraweave(args);
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr("terraweave: error: ")) << args;
    EXPECT_THAT(r.output, HasSubstr(file + " does not match report.json")) << args;
    EXPECT_THAT(r.output, HasSubstr("run the pipeline again")) << args;
    EXPECT_THAT(r.output, HasSubstr("--no-verify")) << args;
  }
  static TempDir* runs;
  TempDir dir;
};

TempDir* RunVerify::runs = nullptr;

TEST_F(RunVerify, DiffFindsATruncatedLayer) {
  const CommandResult same = terraweave("diff run other");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_THAT(same.output, HasSubstr("identical"));
  const fs::path tif = dir / "other/height.tif";
  fs::resize_file(tif, fs::file_size(tif) - 1000);
  expect_refused("diff run other", 2, "height.tif");
  // Without the check, the files as they are: the truncated one differs (it was "identical").
  const CommandResult compared = terraweave("diff --no-verify run other");
  EXPECT_EQ(compared.exit_code, 1) << compared.output;
  EXPECT_THAT(compared.output, HasSubstr("height.tif"));
  EXPECT_THAT(compared.output, Not(HasSubstr("identical")));
}

// Issue #24 item 10: runs in two CRSs are compared cell by cell; diff says so first, naming
// both CRSs.
TEST_F(RunVerify, DiffNamesBothCrssWhenTheyDiffer) {
  ASSERT_EQ(terraweave("-q run " + (runs->path() / "pipeline.yaml").string() +
                       " --out zone32 --set generate.crs=EPSG:32632")
                .exit_code,
            0);
  const CommandResult r = terraweave("diff run zone32");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("the runs' CRSs differ: A is WGS 84 / UTM zone 31N (EPSG:32631), "
                                  "B is WGS 84 / UTM zone 32N (EPSG:32632)"))
      << r.output;
  EXPECT_THAT(terraweave("diff run other").output, Not(HasSubstr("CRSs differ")));
}

// A tiled run's mosaic (height.vrt) is compared with an untiled run's GeoTIFF (height.tif):
// the same pixels are no difference, other pixels are counted (never "only in A / only in B").
TEST_F(RunVerify, DiffComparesATiledRunsMosaicWithAnUntiledTiff) {
  const std::string pipeline = (runs->path() / "pipeline.yaml").string();
  const std::string tiles = " --set 'output.tiles={size: 24, overlap: 2}'";
  ASSERT_EQ(terraweave("-q run " + pipeline + " --out tiled" + tiles).exit_code, 0);
  ASSERT_TRUE(fs::exists(dir / "tiled/height.vrt"));
  const CommandResult same = terraweave("diff tiled run");
  EXPECT_THAT(same.output, Not(HasSubstr("height.vrt: only in A"))) << same.output;
  EXPECT_THAT(same.output, Not(HasSubstr("height.tif: only in B"))) << same.output;
  EXPECT_THAT(same.output, Not(HasSubstr("height.vrt / height.tif"))) << same.output;
  ASSERT_EQ(terraweave("-q run " + pipeline + " --out relief" + tiles + " --set generate.relief=80")
                .exit_code,
            0);
  const CommandResult other = terraweave("diff relief run");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_THAT(other.output, HasSubstr("height.vrt / height.tif")) << other.output;
  EXPECT_THAT(other.output, HasSubstr("pixels differ")) << other.output;
  EXPECT_THAT(other.output, Not(HasSubstr("height.vrt: only in A"))) << other.output;
}

TEST_F(RunVerify, ExportAndViewRefuseFlippedBytes) {
  // 64 bytes of height.tif's pixels flipped: the file still reads, with wrong heights.
  const fs::path tif = dir / "run/height.tif";
  std::uint64_t offset = 0;
  {
    GDALAllRegister();
    const std::unique_ptr<GDALDataset> ds(
        GDALDataset::Open(tif.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_TRUE(ds);
    const char* at = ds->GetRasterBand(1)->GetMetadataItem("BLOCK_OFFSET_0_0", "TIFF");
    ASSERT_NE(at, nullptr);
    offset = std::stoull(at);
  }
  std::string bytes = read_file(tif);
  ASSERT_GT(bytes.size(), offset + 64);
  for (std::size_t i = 0; i < 64; ++i) bytes[offset + i] = char(bytes[offset + i] ^ 0x5a);
  std::ofstream(tif, std::ios::binary | std::ios::trunc) << bytes;

  expect_refused("export run --to unreal --out engine", 1, "height.tif");
  EXPECT_FALSE(fs::exists(dir / "engine"));
  expect_refused("view run --out page.html", 1, "height.tif");
  EXPECT_FALSE(fs::exists(dir / "page.html"));

  const CommandResult exported = terraweave("export run --to unreal --out engine --no-verify");
  EXPECT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_TRUE(fs::exists(dir / "engine"));
  const CommandResult viewed = terraweave("view run --out page.html --no-verify");
  EXPECT_EQ(viewed.exit_code, 0) << viewed.output;
  EXPECT_TRUE(fs::exists(dir / "page.html"));
  // A whole run is read as before.
  const CommandResult whole = terraweave("export other --to unreal --out engine2");
  EXPECT_EQ(whole.exit_code, 0) << whole.output;
}

TEST_F(RunVerify, AMissingFileIsNamed) {
  fs::remove(dir / "run/features.geojson");
  const CommandResult r = terraweave("export run --to godot --out engine");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(
      r.output,
      HasSubstr("features.geojson is missing (report.json names it); run the pipeline again"));
  EXPECT_FALSE(fs::exists(dir / "engine"));
}

}  // namespace
}  // namespace tw::test
