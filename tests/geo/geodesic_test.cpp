#include "geo/geodesic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "geo/metric_frame.hpp"

namespace tw {
namespace {

TEST(GeodesicLength, OneDegreeOfLongitudeAtTheEquator) {
  // The WGS84 equator: 2 pi a / 360 with a = 6378137 m.
  EXPECT_NEAR(geodesic_length({{0.0, 0.0}, {1.0, 0.0}}), 111319.49, 0.01);
}

TEST(GeodesicLength, JfkToHeathrowMatchesGeographicLibDocs) {
  // GeographicLib's documented example: (40.6, -73.8) to (51.6, -0.5) is 5551.76 km.
  EXPECT_NEAR(geodesic_length({{-73.8, 40.6}, {-0.5, 51.6}}) / 1000.0, 5551.76, 0.01);
}

TEST(GeodesicLength, SumsSegmentsAndIgnoresDegenerateInput) {
  const double one = geodesic_length({{0.0, 0.0}, {1.0, 0.0}});
  EXPECT_NEAR(geodesic_length({{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.0}}), one, 1e-6);
  EXPECT_EQ(geodesic_length({{3.0, 45.0}}), 0.0);
  EXPECT_EQ(geodesic_length({}), 0.0);
}

TEST(MetresPerDegree, MatchesTheEllipsoidFormulas) {
  constexpr double a = 6378137.0;
  constexpr double f = 1.0 / 298.257223563;
  const double e2 = f * (2 - f);
  for (double lat : {0.0, 30.0, 45.0, 60.0}) {
    const double phi = lat * std::numbers::pi / 180.0;
    const double w = std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi));
    const double prime_vertical = a / w;                   // N
    const double meridional = a * (1 - e2) / (w * w * w);  // M
    const MetresPerDegree m = metres_per_degree(lat);
    EXPECT_NEAR(m.longitude, prime_vertical * std::cos(phi) * std::numbers::pi / 180.0, 1e-3)
        << lat;
    EXPECT_NEAR(m.latitude, meridional * std::numbers::pi / 180.0, 1e-3) << lat;
  }
}

TEST(CheckMetricLength, TenKilometresInTheLocalFrameIsWithinOnePerMille) {
  // A ~10 km zig-zag near (6.5E, 45.3N) in a transverse Mercator centred on it.
  const std::vector<Vec2> line{{6.45, 45.28}, {6.50, 45.31}, {6.53, 45.30}, {6.56, 45.33}};
  const LengthCheck check = check_metric_length(line, local_transverse_mercator_wkt(6.5, 45.3));
  EXPECT_GT(check.geodesic_m, 9000.0);
  EXPECT_LT(check.geodesic_m, 12000.0);
  EXPECT_LT(std::abs(check.relative_error()), 1e-3);
  // UTM 31N is 3.5 degrees off its central meridian here: its scale error shows.
  const LengthCheck utm = check_metric_length(line, "EPSG:32631");
  EXPECT_GT(std::abs(utm.relative_error()), std::abs(check.relative_error()));
}

TEST(CheckMetricLength, UnknownCrsIsAnError) {
  EXPECT_THROW(check_metric_length({{0, 0}, {1, 0}}, "EPSG:999999"), Error);
}

TEST(LocalTransverseMercator, CentreMapsToTheOrigin) {
  const LengthCheck zero =
      check_metric_length({{10.0, 50.0}, {10.0, 50.0}}, local_transverse_mercator_wkt(10.0, 50.0));
  EXPECT_EQ(zero.metric_m, 0.0);
  EXPECT_NE(local_transverse_mercator_wkt(10.0, 50.0).find("Transverse Mercator"),
            std::string::npos);
}

}  // namespace
}  // namespace tw
