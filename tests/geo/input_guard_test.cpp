// Network and file access of inputs (issue #9 item 8, docs/robustness.md "Network and files").
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <fstream>

#include "core/error.hpp"
#include "geo/heightfield.hpp"
#include "geo/input_guard.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

TEST(InputGuard, NamesTheNetworkPartOfAPath) {
  EXPECT_EQ(network_part_of("/vsicurl/https://example.com/dem.tif"), "/vsicurl");
  EXPECT_EQ(network_part_of("/vsicurl?url=http%3A%2F%2Fexample.com%2Fdem.tif"), "/vsicurl");
  EXPECT_EQ(network_part_of("/vsicurl_streaming/http://x/y.tif"), "/vsicurl");
  EXPECT_EQ(network_part_of("/vsizip//vsicurl/http://x/a.zip/a.tif"), "/vsicurl");
  EXPECT_EQ(network_part_of("/vsitar//vsis3/bucket/a.tar/a.tif"), "/vsis3");
  EXPECT_EQ(network_part_of("/VSIGS/bucket/a.tif"), "/vsigs");
  for (const char* fs :
       {"/vsiaz/", "/vsiadls/", "/vsioss/", "/vsiswift/", "/vsiwebhdfs/", "/vsihdfs/"}) {
    EXPECT_EQ(network_part_of(std::string(fs) + "c/a.tif"),
              std::string(fs).substr(0, std::string(fs).size() - 1));
  }
  EXPECT_EQ(network_part_of("https://example.com/roads.gpkg"), "https:");
  EXPECT_EQ(network_part_of("FTP://example.com/roads.gpkg"), "ftp:");
  EXPECT_EQ(network_part_of("WFS:http://example.com/wfs"), "wfs:");
  EXPECT_EQ(network_part_of("PG:host=db.example.com dbname=gis"), "pg:");
  EXPECT_EQ(network_part_of("MySQL:gis,host=db"), "mysql:");
  EXPECT_EQ(network_part_of("/base/dir/http:/example.com/x.tif"), "http:");  // normalised
  EXPECT_EQ(network_part_of("EPSG:32631"), "");
  // Local names that merely look alike stay local.
  for (const char* local : {"/data/http/dem.tif", "/data/https_mirror/dem.tif", "dem_vsicurl.tif",
                            "/vsizip/maps.zip/roads.shp", "/vsimem/x.tif", "C-http:x"}) {
    EXPECT_EQ(network_part_of(local), "") << local;
  }
}

TEST(InputGuard, RefusesNetworkPathsNamingTheKeyUnlessAllowed) {
  try {
    check_input_path("/vsis3/bucket/dem.tif", "heightfield", false);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "heightfield: '/vsis3/bucket/dem.tif' reaches the network (/vsis3); terraweave "
                 "reads local files unless run with --allow-network");
  }
  EXPECT_NO_THROW(check_input_path("/vsis3/bucket/dem.tif", "heightfield", true));
  EXPECT_NO_THROW(check_input_path("/data/dem.tif", "heightfield", false));
}

// The geo readers check too, for library callers that skip the pipeline.
TEST(InputGuard, TheReadersRefuseNetworkPathsWhileNetworkIsOff) {
  set_network_access(false);
  try {
    read_heightfield("/vsicurl/http://127.0.0.1:9/dem.tif");
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("heightfield: '/vsicurl/http://127.0.0.1:9/dem.tif' reaches "
                                    "the network (/vsicurl)"));
  }
}

// A CRS string is never read from a file: OGR would otherwise read any local file named there
// (and show parts of it in errors).
TEST(InputGuard, ACrsIsNeverReadFromAFile) {
  OGRSpatialReference utm;
  ASSERT_EQ(utm.importFromEPSG(32631), OGRERR_NONE);
  char* wkt = nullptr;
  utm.exportToWkt(&wkt);
  const std::string text = wkt;
  CPLFree(wkt);
  test::TempDir dir;
  std::ofstream(dir / "utm.wkt") << text;
  const std::string file = (dir / "utm.wkt").string();
  OGRSpatialReference plain;
  ASSERT_EQ(plain.SetFromUserInput(file.c_str()), OGRERR_NONE);  // what OGR does by default
  OGRSpatialReference srs;
  EXPECT_FALSE(import_crs(srs, file));
  EXPECT_TRUE(import_crs(srs, text));
  EXPECT_TRUE(srs.IsSame(&utm));
  EXPECT_TRUE(import_crs(srs, "EPSG:4326"));
  set_network_access(false);
  EXPECT_FALSE(import_crs(srs, "http://127.0.0.1:9/crs.wkt"));
  EXPECT_FALSE(network_access_allowed());
}

}  // namespace
}  // namespace tw
