// YAML and pipeline files that must be refused (issue #9 items 4-6): repeated keys, a second
// document, empty --set values, absurd sizes, and paths that are not a pipeline file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "core/error.hpp"
#include "pipeline/config.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* const kMinimal = R"(version: 1
seed: 7
heightfield: dem.tif
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 8 }
)";

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "no tw::Error";
}

std::string parse_error(const std::string& text, const std::vector<Override>& overrides = {}) {
  return error_of([&] { parse_pipeline(text, "p.yaml", "/base", overrides); });
}

TEST(PipelineConfigHardening, ARepeatedKeyIsAnErrorInEveryMapping) {
  EXPECT_EQ(parse_error(std::string(kMinimal) + "seed: 8\n"),
            "p.yaml:6:1: seed: duplicate key (first at line 2)");
  // Nested mappings (a flow map in a class) and class names alike.
  EXPECT_EQ(parse_error(R"(version: 1
heightfield: dem.tif
features:
  roads: { source: map.gpkg, kind: road, width: 8, width: 9 }
)"),
            "p.yaml:4:52: width: duplicate key (first at line 4)");
  EXPECT_THAT(parse_error(R"(version: 1
heightfield: dem.tif
features:
  roads: { source: a.gpkg, kind: road, width: 8 }
  roads: { source: b.gpkg, kind: road, width: 8 }
)"),
              HasSubstr("p.yaml:5:3: roads: duplicate key (first at line 4)"));
}

TEST(PipelineConfigHardening, ASecondYamlDocumentIsAnError) {
  EXPECT_THAT(parse_error(std::string(kMinimal) + "---\nseed: 9\n"),
              HasSubstr("p.yaml:6: a second YAML document"));
  // What yaml-cpp 0.7's LoadAll looped on forever (fuzz/pipeline_parser): a flow indicator
  // where a block mapping's key should start reads as the start of a second document.
  EXPECT_THAT(parse_error(test::read_file(test::source_dir() /
                                          "fuzz/corpus/pipeline_parser/loadall_hang.yaml")),
              HasSubstr("p.yaml:2: a second YAML document, or text after the first"));
  // One document (even with an explicit start) is fine.
  EXPECT_EQ(parse_pipeline(std::string("---\n") + kMinimal, "p.yaml", "/base", {}).seed, 7u);
}

// Issue #24 item 7: a Latin-1 byte ended as nlohmann's "invalid UTF-8 byte" with no file, line
// or key (found by fuzz/pipeline_parser); 1e400 must be a located error too.
TEST(PipelineConfigHardening, NonUtf8TextAndOutOfRangeNumbersAreLocatedErrors) {
  const std::string latin1 = std::string(kMinimal) +
                             "  hedges: { source: map.gpkg, kind: road, width: 3, where: \"name = "
                             "'S\xe3o Jo\xe3o'\" }\n";
  EXPECT_EQ(parse_error(latin1),
            "p.yaml:6: not UTF-8 text (a pipeline is UTF-8; convert the file, e.g. iconv -f "
            "LATIN1 -t UTF-8)");
  EXPECT_THAT(parse_error(kMinimal, {parse_override("features.roads.where=name = 'S\xe3o'")}),
              HasSubstr("--set:1: not UTF-8 text"));
  // The same text in UTF-8 is read.
  const std::string utf8 = std::string(kMinimal) +
                           "  hedges: { source: map.gpkg, kind: road, width: 3, where: \"name = "
                           "'S\xc3\xa3o Jo\xc3\xa3o'\" }\n";
  EXPECT_EQ(parse_pipeline(utf8, "p.yaml", "/base", {}).features.size(), 2u);
  EXPECT_THAT(parse_error(kMinimal, {parse_override("features.roads.width=1e400")}),
              HasSubstr("--set features.roads.width=1e400: features.roads.width:"));
  EXPECT_THAT(parse_error(std::string(kMinimal) + "resolution: 1e400\n"),
              HasSubstr("p.yaml:6:13: resolution:"));
}

// Our own check (not GDAL's CPLIsUTF8: reading a pipeline loads no GDAL, docs/performance.md):
// well-formed UTF-8 as JSON requires it, so overlong forms, surrogates, code points above
// U+10FFFF and a sequence cut short are refused with their line.
TEST(PipelineConfigHardening, TheUtf8CheckFollowsRfc3629) {
  const std::string good = std::string(kMinimal) + "# \xe2\x82\xac \xf0\x9f\x8c\x8d \xc3\xa3\n";
  EXPECT_EQ(parse_pipeline(good, "p.yaml", "/base", {}).seed, 7u);
  for (const char* bad : {"\xc0\xaf", "\xe0\x80\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80",
                          "\xf5\x80\x80\x80", "\xe2\x82", "\x80"}) {
    const std::string text = std::string(kMinimal) + "# a" + bad + "\n";
    EXPECT_EQ(parse_error(text),
              "p.yaml:6: not UTF-8 text (a pipeline is UTF-8; convert the file, e.g. iconv -f "
              "LATIN1 -t UTF-8)")
        << bad;
  }
}

TEST(PipelineConfigHardening, AnEmptySetValueIsAnError) {
  EXPECT_EQ(error_of([] { parse_override("seed="); }),
            "--set seed=: empty value (for an empty string write seed=\"\")");
  // An explicitly empty string reaches the reader, which names the key.
  EXPECT_THAT(parse_error(kMinimal, {parse_override("seed=\"\"")}),
              HasSubstr("--set seed=\"\": seed: expected a non-negative integer"));
}

TEST(PipelineConfigHardening, AbsurdReliefAndWidthsAreKeyErrors) {
  EXPECT_EQ(parse_error(R"(version: 1
generate: { relief: 1e308 }
features:
  roads: { source: map.gpkg, kind: road, width: 8 }
)"),
            "p.yaml:2:21: generate.relief: must be at most 100000 m, got 1e+308");
  EXPECT_EQ(parse_error(kMinimal, {parse_override("features.roads.width=1e12")}),
            "--set features.roads.width=1e12: features.roads.width: must be at most 100000 m, "
            "got 1e+12");
  // Profile heights and lengths too: a ridge of 1e308 m made every height infinite.
  EXPECT_EQ(parse_error(R"(version: 1
heightfield: dem.tif
features:
  ridges: { source: map.gpkg, kind: ridge, width: 8, profile: { height: 1e308 } }
)"),
            "p.yaml:4:73: features.ridges.profile.height: must be at most 100000 m, got 1e+308");
}

TEST(PipelineConfigHardening, OnlyARegularFileOfBoundedSizeIsLoaded) {
  test::TempDir dir;
  EXPECT_EQ(error_of([&] { load_pipeline(dir.path()); }),
            dir.path().string() + ": is a folder; give the pipeline file (YAML) itself");
  EXPECT_EQ(error_of([] { load_pipeline("/dev/zero"); }),
            "/dev/zero: not a regular file; a pipeline file is a YAML file");
  const fs::path big = dir / "big.yaml";
  {
    std::ofstream out(big);
    out << kMinimal << "# ";
    out << std::string(kMaxPipelineFileBytes, 'x') << "\n";
  }
  EXPECT_EQ(error_of([&] { load_pipeline(big); }),
            big.string() + ": over 16 MiB; a pipeline file is a few KiB of YAML");
}

}  // namespace
}  // namespace tw
