// synthesize() over a mix of exemplars (synth/exemplar_mix.hpp): bound stretches use their
// exemplar, the renderer reads every channel of each piece's own exemplar, and the placements
// file keeps the exemplar of each piece (old files stay readable).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/exemplar_mix.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/placements_io.hpp"
#include "synth/render.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"
#include "synth_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

// A band exemplar whose opaque texels all have height `height`.
Exemplar band_of_height(int width, unsigned seed, float height) {
  Exemplar e = test::band_exemplar(width, 8, 2, 5, seed);
  const int h = e.channel_index("height"), a = e.channel_index("A");
  for (std::size_t t = 0; t < std::size_t(e.width) * e.height; ++t)
    e.texels[t * 5 + std::size_t(h)] = e.texels[t * 5 + std::size_t(a)] > 0.5f ? height : 0.0f;
  return e;
}

struct BoundMix {
  Exemplar plain = band_of_height(30, 3, 1.0f), deck = band_of_height(20, 9, 7.0f);
  Ribbon ribbon = make_ribbon(Curve{{{0, 0}, {30, 0}}, false}, {5.0, 2.0});
  MixedExemplar mix = mix_exemplars({&plain, &deck}, mix_gap(1.0, 2.0, 5.0));
  SynthParams params;
  BoundMix() {
    params.scale = 1.0;
    params.mix = mix.layout;
    // Pieces 5..9 (x in [10, 20] m) are the deck; the rest the plain exemplar.
    for (std::size_t i = 0; i < ribbon.pieces.size(); ++i)
      params.piece_exemplars.push_back(i >= 5 && i < 10 ? std::vector<std::uint8_t>{0, 1}
                                                        : std::vector<std::uint8_t>{1, 0});
  }
};

TEST(MixSynthesis, BoundStretchesRenderTheirOwnExemplar) {
  const BoundMix m;
  ASSERT_EQ(m.ribbon.pieces.size(), 15u);
  const GridSpec canvas = test::canvas_around(m.ribbon, 0.25, 2.0);
  auto backend = detail::make_cpu_backend();
  const Synthesis s =
      detail::synthesize_on(*backend, m.mix.atlas, m.ribbon, canvas, nullptr, m.params);
  for (std::size_t i = 0; i < s.placements.size(); ++i) {
    const Placement& p = s.placements[i];
    const int expected = i >= 5 && i < 10 ? 1 : 0;
    EXPECT_EQ(p.exemplar, expected) << "piece " << i;
    EXPECT_EQ(m.mix.layout.exemplar_at(p.ux, p.uy), expected) << "piece " << i;
  }
  EXPECT_EQ(s.pieces_per_exemplar, (std::vector<int>{10, 5}));
  EXPECT_EQ(s.exemplar_switches, 2);
  // Every covered pixel shows the height of its piece's exemplar: 7 on the deck, 1 elsewhere.
  const RenderedPattern out =
      render_pattern(m.mix.atlas, m.ribbon, s, canvas, Window::whole(canvas), false);
  const int h = m.mix.atlas.channel_index("height");
  int deck = 0, plain = 0;
  for (int r = 0; r < canvas.height; ++r)
    for (int c = 0; c < canvas.width; ++c) {
      if (out.coverage.at(c, r) < 0.999f) continue;
      const double x = canvas.pixel_centre_world(c, r).x;
      if (std::abs(x - 10.0) < 0.5 || std::abs(x - 20.0) < 0.5 || x < 0.0 || x > 30.0) continue;
      const bool on_deck = x > 10.0 && x < 20.0;
      EXPECT_NEAR(out.channels[std::size_t(h)].at(c, r), on_deck ? 7.0f : 1.0f, 1e-4f)
          << "pixel " << c << ", " << r;
      ++(on_deck ? deck : plain);
    }
  EXPECT_GT(deck, 100);
  EXPECT_GT(plain, 200);
}

TEST(MixSynthesis, PlacementsKeepEachPiecesExemplar) {
  const BoundMix m;
  const GridSpec canvas = test::canvas_around(m.ribbon, 0.5, 2.0);
  auto backend = detail::make_cpu_backend();
  SynthParams params = m.params;
  params.piece_exemplars.clear();  // a free mix
  params.switch_cost = 64;
  const Synthesis s =
      detail::synthesize_on(*backend, m.mix.atlas, m.ribbon, canvas, nullptr, params);
  const std::string text = placements_to_json(s, m.mix.atlas.path);
  EXPECT_NE(text.find("\"version\": 2"), std::string::npos);
  const Synthesis back = placements_from_json(text, "mix.json");
  ASSERT_TRUE(back.mix.has_value());
  EXPECT_EQ(back.mix->x0, m.mix.layout.x0);
  EXPECT_EQ(back.mix->gap, m.mix.layout.gap);
  EXPECT_EQ(back.pieces_per_exemplar, s.pieces_per_exemplar);
  EXPECT_EQ(back.exemplar_switches, s.exemplar_switches);
  ASSERT_EQ(back.placements.size(), s.placements.size());
  for (std::size_t i = 0; i < s.placements.size(); ++i) {
    EXPECT_EQ(back.placements[i].exemplar, s.placements[i].exemplar);
    EXPECT_EQ(back.placements[i].ux, s.placements[i].ux);  // back in atlas columns
  }
  // The file stores ux in the piece's own exemplar.
  const auto doc = nlohmann::json::parse(text);
  const Placement& first = s.placements.front();
  EXPECT_EQ(doc["placements"][0]["ux"].get<int>(),
            first.ux - m.mix.layout.x0[std::size_t(first.exemplar)]);
  // Without a mix: version 1 and no exemplar keys, as before.
  SynthParams single;
  single.scale = 1.0;
  const Synthesis one = detail::synthesize_on(*backend, m.plain, m.ribbon, canvas, nullptr, single);
  const std::string old = placements_to_json(one, "plain");
  EXPECT_NE(old.find("\"version\": 1"), std::string::npos);
  EXPECT_EQ(old.find("exemplar\": 0"), std::string::npos);
  EXPECT_FALSE(placements_from_json(old, "old.json").mix.has_value());
}

// Rules in order: a bridge rule whose line predicate matched binds every piece to the deck; a
// junction rule binds the pieces within its distance; the rest use the unnamed exemplar.
TEST(MixSynthesis, JunctionAndLineRulesBindTheirPieces) {
  const Exemplar plain = band_of_height(30, 3, 1.0f), crossing = band_of_height(24, 5, 3.0f),
                 deck = band_of_height(20, 9, 7.0f);
  const Ribbon ribbon = make_ribbon(Curve{{{0, 0}, {60, 0}}, false}, {5.0, 2.0});
  const MixedExemplar mix = mix_exemplars({&plain, &crossing, &deck}, mix_gap(1.0, 2.0, 5.0));
  const std::vector<Vec2> junctions = {{30.0, 0.0}};
  const GridSpec canvas = test::canvas_around(ribbon, 0.5, 2.0);
  auto backend = detail::make_cpu_backend();
  SynthParams params;
  params.scale = 1.0;
  params.mix = mix.layout;
  params.switch_cost = 16;
  for (const bool on_bridge : {false, true}) {
    SCOPED_TRACE(on_bridge ? "the line is a bridge" : "the line is on the ground");
    params.piece_exemplars =
        bind_pieces(ribbon, 3, {{2, on_bridge, 0.0}, {1, true, 8.0}}, junctions);
    const Synthesis s = detail::synthesize_on(*backend, mix.atlas, ribbon, canvas, nullptr, params);
    int near = 0;
    for (std::size_t i = 0; i < ribbon.pieces.size(); ++i) {
      // Piece i spans x in [2i, 2i + 2]: within 8 m of x = 30 when 22 <= 2i + 2 and 2i <= 38.
      const bool close = 2.0 * double(i) + 2.0 >= 22.0 && 2.0 * double(i) <= 38.0;
      const int expected = on_bridge ? 2 : close ? 1 : 0;
      EXPECT_EQ(s.placements[i].exemplar, expected) << "piece " << i;
      near += close ? 1 : 0;
    }
    EXPECT_EQ(near, 10);
    EXPECT_EQ(s.exemplar_switches, on_bridge ? 0 : 2);
  }
}

// mix_gap's bound holds for the footprints of folded and tight curves (synthesize checks it).
TEST(MixSynthesis, GapBoundsEveryFootprintsReach) {
  for (const char* shape : {"line", "s-curve", "circle", "heart", "hairpin"}) {
    const Ribbon ribbon = make_ribbon(make_shape(shape, 40.0), {10.0, 3.0});
    const int column = detail::column_count(10.0, 2.0);
    std::vector<detail::PieceFootprint> pieces;
    for (const Piece& piece : ribbon.pieces)
      pieces.push_back(detail::make_piece_footprint(piece, 2.0, column, GridSpec{}, nullptr));
    const int needed = detail::mix_gap(pieces);
    EXPECT_LE(needed, mix_gap(2.0, 3.0, 10.0)) << shape;
    EXPECT_GT(needed, 6) << shape;  // a piece reads at least its 3 m x 2 texels
  }
}

}  // namespace
}  // namespace tw
