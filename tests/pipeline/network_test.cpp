// The network switch as a second line of defence (issue #9 item 8): a local VRT whose band
// points at /vsicurl/http://127.0.0.1:<port>/... passes the path check, so only GDAL's own
// switch stands between it and a request. A listening socket counts the connections.
#include <arpa/inet.h>
#include <cpl_conv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>

#include "core/error.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A TCP listener on 127.0.0.1 that never answers; counts the connections made to it.
class Listener {
 public:
  Listener() {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof address;
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), size) != 0 || ::listen(fd_, 8) != 0 ||
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
      ADD_FAILURE() << "no listener";
    }
    port_ = ntohs(address.sin_port);
  }
  ~Listener() { ::close(fd_); }
  int port() const { return port_; }
  int connections() {
    int n = 0;
    for (int c; (c = ::accept(fd_, nullptr, nullptr)) >= 0; ++n) ::close(c);
    return n;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(NetworkSwitch, AVrtPointingAtAUrlSendsNoRequestUnlessAllowed) {
  test::TempDir dir;
  test::write_dem(dir / "dem.tif");
  test::write_layer(dir / "map.gpkg", "roads",
                    {{"LINESTRING (500100 5000100, 500300 5000300)", 6.0}});
  Listener listener;
  const std::string url =
      "/vsicurl/http://127.0.0.1:" + std::to_string(listener.port()) + "/dem.tif";
  std::ofstream(dir / "net.vrt") << R"(<VRTDataset rasterXSize="64" rasterYSize="64">
  <SRS>EPSG:32631</SRS>
  <GeoTransform>500000, 10, 0, 5000640, 0, -10</GeoTransform>
  <VRTRasterBand dataType="Float32" band="1">
    <SimpleSource>
      <SourceFilename relativeToVRT="0">)"
                                 << url << R"(</SourceFilename>
      <SourceBand>1</SourceBand>
    </SimpleSource>
  </VRTRasterBand>
</VRTDataset>
)";
  const PipelineConfig config = parse_pipeline(R"(version: 1
heightfield: net.vrt
output: { dir: out }
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 6 }
)",
                                               "net.yaml", dir.path());
  RunOptions options;
  options.write_outputs = false;
  EXPECT_THROW(run_pipeline(config, options), Error);
  EXPECT_EQ(listener.connections(), 0);

  // The control: allowed, GDAL connects (and gives up after a second without an answer).
  CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "1");
  CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "0");
  options.allow_network = true;
  EXPECT_THROW(run_pipeline(config, options), Error);
  EXPECT_GE(listener.connections(), 1);
  CPLSetConfigOption("GDAL_HTTP_TIMEOUT", nullptr);
  CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", nullptr);
  options.allow_network = false;
  EXPECT_THROW(run_pipeline(config, options), Error);  // and off again
  EXPECT_EQ(listener.connections(), 0);
}

// A local GeoJSON whose `crs` is a link: GDAL's reader fetches it with CPLHTTPFetch (not
// /vsicurl), so the path check cannot see it; the HTTP fetch switch refuses it.
TEST(NetworkSwitch, AGeoJsonCrsLinkSendsNoRequestUnlessAllowed) {
  test::TempDir dir;
  test::write_dem(dir / "dem.tif");
  Listener listener;
  std::ofstream(dir / "roads.geojson")
      << R"({"type": "FeatureCollection", "crs": {"type": "link", "properties": {"href": "http://127.0.0.1:)"
      << listener.port() << R"(/crs.wkt", "type": "ogcwkt"}}, "features": [{"type": "Feature",
    "properties": {}, "geometry": {"type": "LineString",
    "coordinates": [[500100, 5000100], [500300, 5000300]]}}]})";
  const PipelineConfig config = parse_pipeline(R"(version: 1
heightfield: dem.tif
output: { dir: out }
features:
  roads: { source: roads.geojson, kind: road, width: 6 }
)",
                                               "link.yaml", dir.path());
  RunOptions options;
  options.write_outputs = false;
  try {
    run_pipeline(config, options);
  } catch (const Error&) {  // without its CRS the layer may be refused: either way, no request
  }
  EXPECT_EQ(listener.connections(), 0);

  // The control: allowed, GDAL asks. Each connection is closed at once, so that the fetch
  // fails fast instead of waiting out OSR's own 10 s timeout.
  std::atomic<bool> done = false;
  std::atomic<int> answered = 0;
  std::thread closer([&] {
    while (!done) {
      answered += listener.connections();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
  options.allow_network = true;
  try {
    run_pipeline(config, options);
  } catch (const Error&) {
  }
  done = true;
  closer.join();
  EXPECT_GE(answered + listener.connections(), 1);
}

// The CLI flag reaches the run: the same URL heightfield is refused without it, with a message
// naming the key; with it, GDAL is asked (and fails on the closed port, naming the path).
TEST(NetworkSwitch, TheCliRefusesUrlsWithoutAllowNetwork) {
  test::TempDir dir;
  test::write_layer(dir / "map.gpkg", "roads",
                    {{"LINESTRING (500100 5000100, 500300 5000300)", 6.0}});
  std::ofstream(dir / "p.yaml")
      << "version: 1\nheightfield: /vsicurl/http://127.0.0.1:9/dem.tif\n"
         "features:\n  roads: { source: map.gpkg, kind: road, width: 6 }\n";
  const std::string command = "cd '" + dir.path().string() + "' && '" +
                              test::terraweave_binary().string() + "' validate p.yaml";
  test::CommandResult r = test::run_command(command);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output,
            "terraweave: error: p.yaml:2:14: heightfield: '/vsicurl/http://127.0.0.1:9/dem.tif' "
            "reaches the "
            "network (/vsicurl); terraweave reads local files unless run with --allow-network\n");
  r = test::run_command("GDAL_HTTP_TIMEOUT=1 GDAL_HTTP_MAX_RETRY=0 " + command +
                        " --allow-network");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("heightfield: /vsicurl/http://127.0.0.1:9/dem.tif: "));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("reaches the network")));
}

}  // namespace
}  // namespace tw
