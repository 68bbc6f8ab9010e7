// `terraweave view` (issue #12 item 6): the page loads in headless Chromium (Debian's, with
// SwiftShader for WebGL) from a file:// URL with no network, and its screenshot shows the
// terrain: not blank, many colours, the splat's base green and the sky around it. A tiled run
// (output.tiles) is read through its VRT mosaics and gives the untiled run's page.
#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class View : public ::testing::Test {
 protected:
  void SetUp() override {
    write_layer(dir / "map.gpkg", "roads",
                {{"LINESTRING (500050 4999600, 500300 4999800, 500600 4999700)", 12.0}});
    std::ofstream(dir / "pipeline.yaml") << R"(version: 1
seed: 3
generate: { width: 64, height: 48, pixel_size: 10, relief: 60, origin: [500000, 5000000] }
output: { dir: out, preview: false, exr: false }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 12 }
)";
  }
  // `terraweave ARGS` in the test's folder.
  CommandResult terraweave(const std::string& args) const {
    return run_command("cd '" + dir.path().string() + "' && '" + terraweave_binary().string() +
                       "' " + args);
  }
  // Opens `page` in headless Chromium and checks its screenshot shows terrain under a sky.
  void expect_terrain_on_screen(const fs::path& page) const {
    const fs::path png = page.parent_path() / (page.stem().string() + "_shot.png");
    const CommandResult shot =
        run_command("cd '" + page.parent_path().string() +
                    "' && timeout 90 chromium --headless --no-sandbox --use-angle=swiftshader "
                    "--enable-unsafe-swiftshader --window-size=400,300 --virtual-time-budget=8000 "
                    "--screenshot='" +
                    png.string() + "' 'file://" + page.string() + "' 2>&1");
    ASSERT_TRUE(fs::exists(png)) << shot.output;

    auto input = OIIO::ImageInput::open(png.string());
    ASSERT_TRUE(input);
    const OIIO::ImageSpec spec = input->spec();
    ASSERT_EQ(spec.width, 400);
    std::vector<unsigned char> rgb(std::size_t(spec.width) * spec.height * 3);
    ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeUInt8, rgb.data()));
    std::set<int> colours;
    double sum = 0, sum2 = 0;
    int green = 0, sky = 0;
    const std::size_t pixels = rgb.size() / 3;
    for (std::size_t p = 0; p < pixels; ++p) {
      const int r = rgb[3 * p], g = rgb[3 * p + 1], b = rgb[3 * p + 2];
      colours.insert(r << 16 | g << 8 | b);
      const double l = 0.299 * r + 0.587 * g + 0.114 * b;
      sum += l, sum2 += l * l;
      green += g > r + 10 && g > b + 10;  // the base, low ground
      sky += std::abs(r - 0x9d) + std::abs(g - 0xb4) + std::abs(b - 0xc8) < 6;  // clear colour
    }
    const double variance = sum2 / pixels - (sum / pixels) * (sum / pixels);
    EXPECT_GT(variance, 100.0) << page;
    EXPECT_GT(colours.size(), 500u) << page;
    EXPECT_GT(green, int(pixels / 100)) << page << ": no terrain colours";
    EXPECT_GT(sky, int(pixels / 20)) << page << ": the terrain should not fill the whole window";
    EXPECT_LT(sky, int(pixels * 3 / 4)) << page << ": the terrain should fill a good part of it";
  }
  TempDir dir;
};

TEST_F(View, APageOfARunShowsTheTerrainInAHeadlessBrowser) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml").exit_code, 0);
  const CommandResult view = terraweave("view out --out page.html");
  ASSERT_EQ(view.exit_code, 0) << view.output;
  const std::string page = read_file(dir / "page.html");
  EXPECT_THAT(page, Not(HasSubstr("http://")));  // nothing to fetch: three.js is inlined
  EXPECT_THAT(page, Not(HasSubstr("https://")));
  expect_terrain_on_screen(dir / "page.html");
}

// Issue #22 item 7: nodata is no terrain. Over Luxembourg's DEM (nodata outside the country,
// 45 %) the page draws exactly the triangles whose three corners have heights, counted by the
// page itself in Chromium and here from the page's data.
TEST_F(View, NodataIsLeftOutOfTheMesh) {
  const CommandResult run = terraweave("-q run '" +
                                       (source_dir() / "pipelines/luxembourg.yaml").string() +
                                       "' --set resolution=500 --out lux");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_EQ(terraweave("view lux --out lux.html").exit_code, 0);
  const std::string page = read_file(dir / "lux.html");
  const std::string open = R"(<script id="data" type="application/json">)";
  const std::size_t begin = page.find(open) + open.size();
  const nlohmann::json data =
      nlohmann::json::parse(page.substr(begin, page.find("</script>", begin) - begin));
  const int mw = data["mesh"]["width"], mh = data["mesh"]["height"];
  const nlohmann::json& z = data["mesh"]["heights"];
  // three.js's PlaneGeometry: cell (i, j) is the triangles (a, b, d) and (b, c, d).
  int expected = 0;
  for (int j = 0; j + 1 < mh; ++j) {
    for (int i = 0; i + 1 < mw; ++i) {
      const bool a = !z[j * mw + i].is_null(), b = !z[(j + 1) * mw + i].is_null();
      const bool c = !z[(j + 1) * mw + i + 1].is_null(), d = !z[j * mw + i + 1].is_null();
      expected += (a && b && d) + (b && c && d);
    }
  }
  const int all = 2 * (mw - 1) * (mh - 1);
  ASSERT_GT(expected, all / 4);  // Luxembourg itself...
  ASSERT_LT(expected, all * 3 / 4);  // ...and much nodata around it
  const CommandResult dom = run_command(
      "cd '" + dir.path().string() +
      "' && timeout 90 chromium --headless --no-sandbox --use-angle=swiftshader "
      "--enable-unsafe-swiftshader --virtual-time-budget=8000 --dump-dom 'file://" +
      (dir / "lux.html").string() + "' 2>/dev/null");
  EXPECT_THAT(dom.output, HasSubstr("data-triangles=\"" + std::to_string(expected) + "\""))
      << "expected " << expected << " of " << all << " triangles";
}

TEST_F(View, ATiledRunIsViewedThroughItsMosaicsAsTheUntiledRun) {
  // Both run folders are named "out" (the page's title), under different parents.
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set output.dir=untiled/out").exit_code, 0);
  const CommandResult tiled = terraweave(
      "-q run pipeline.yaml --set output.dir=tiled/out --set 'output.tiles={size: 24, overlap: "
      "2}'");
  ASSERT_EQ(tiled.exit_code, 0) << tiled.output;
  ASSERT_TRUE(fs::exists(dir / "tiled/out/height.vrt"));
  ASSERT_FALSE(fs::exists(dir / "tiled/out/height.tif"));  // the case this test is about

  const CommandResult view = terraweave("view tiled/out --out tiled.html");
  ASSERT_EQ(view.exit_code, 0) << view.output;
  ASSERT_EQ(terraweave("view untiled/out --out untiled.html").exit_code, 0);
  // The mosaics hold the untiled run's pixels, so the page is the same, byte for byte.
  EXPECT_TRUE(read_file(dir / "tiled.html") == read_file(dir / "untiled.html"));
  expect_terrain_on_screen(dir / "tiled.html");
}

// Issue #24 item 10: a tiled run with a tile gone names the tile (read without the check of
// report.json, which names it too) and says what to do; nothing is written.
TEST_F(View, ATiledRunWithATileMissingNamesTheTile) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set output.dir=tiled/out --set "
                       "'output.tiles={size: 24, overlap: 2}'")
                .exit_code,
            0);
  const std::string vrt = read_file(dir / "tiled/out/height.vrt");
  const std::size_t at = vrt.find("<SourceFilename");
  ASSERT_NE(at, std::string::npos);
  const std::size_t start = vrt.find('>', at) + 1;
  const std::string tile = vrt.substr(start, vrt.find('<', start) - start);
  ASSERT_TRUE(fs::remove(dir / "tiled/out" / tile)) << tile;
  const CommandResult view = terraweave("view tiled/out --no-verify --out page.html 2>&1");
  EXPECT_EQ(view.exit_code, 1) << view.output;
  EXPECT_THAT(view.output, HasSubstr(".vrt: its tile ")) << view.output;
  EXPECT_THAT(view.output, HasSubstr(tile + " is missing")) << view.output;
  EXPECT_THAT(view.output, HasSubstr("render that tile again"));
  EXPECT_FALSE(fs::exists(dir / "page.html"));
}

TEST_F(View, ARunWithoutItsLayersIsNamedInTheError) {
  ASSERT_EQ(terraweave("-q run pipeline.yaml --set output.dir=tiled/out --set "
                       "'output.tiles={size: 24, overlap: 2}'")
                .exit_code,
            0);
  fs::remove(dir / "tiled/out/avoidance.vrt");
  // Checked against report.json first (issue #24); without the check, the layer is named.
  const CommandResult view = terraweave("view tiled/out --out page.html");
  EXPECT_NE(view.exit_code, 0);
  EXPECT_THAT(view.output, HasSubstr("avoidance.vrt is missing (report.json names it)"));
  const CommandResult unchecked = terraweave("view tiled/out --out page.html --no-verify");
  EXPECT_NE(unchecked.exit_code, 0);
  EXPECT_THAT(unchecked.output, HasSubstr("the run wrote no avoidance.vrt"));
  EXPECT_FALSE(fs::exists(dir / "page.html"));
}

}  // namespace
}  // namespace tw::test
