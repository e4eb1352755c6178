// io/svg_plot: document structure, escaping, line breaks at NaN, nice ticks, and decimation that keeps the spikes.
#include "drillwave/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "svg_points.hpp"

#include "drillwave/io/svg_heatmap.hpp"

namespace drillwave::io {
namespace {

std::string Svg(const Figure& figure) {
  std::ostringstream out;
  WriteSvg(figure, out);
  return out.str();
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

using drillwave::testing::PolylinePoints;

Series Sine(const std::string& label, int n, double amplitude) {
  Series s{label, {}, {}};
  for (int i = 0; i < n; ++i) {
    s.x.push_back(0.1 * i);
    s.y.push_back(amplitude * std::sin(0.1 * i));
  }
  return s;
}

TEST(WriteSvg, IsAnSvgDocumentWithOnePolylinePerSeries) {
  const Figure figure{"two panels",
                      "time [s]",
                      {Panel{"speed [rad/s]", {Sine("top", 200, 1), Sine("bit", 200, 2)}},
                       Panel{"torque [N m]", {Sine("on bit", 50, 1e4)}}}};
  const std::string svg = Svg(figure);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(Count(svg, "<polyline"), 3u);
  EXPECT_EQ(Count(svg, "<g>"), 2u);
  EXPECT_EQ(Count(svg, "<g>") + Count(svg, "<g "), Count(svg, "</g>"));  // panels and legends
  for (const char* text : {">two panels<", ">time [s]<", ">speed [rad/s]<", ">torque [N m]<", ">top<", ">bit<", ">on bit<"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  // Two series in one panel get different colours.
  EXPECT_NE(svg.find("#1f77b4"), std::string::npos);
  EXPECT_NE(svg.find("#d62728"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(WriteSvg, EscapesText) {
  Series s = Sine("a<b & \"c\"", 10, 1);
  const std::string svg = Svg(Figure{"<script>x</script> & 'q'", "t < 5", {Panel{"y > 0", {s}}}});
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_NE(svg.find("&lt;script&gt;x&lt;/script&gt; &amp; &apos;q&apos;"), std::string::npos);
  EXPECT_NE(svg.find(">t &lt; 5<"), std::string::npos);
  EXPECT_NE(svg.find(">y &gt; 0<"), std::string::npos);
  EXPECT_NE(svg.find(">a&lt;b &amp; &quot;c&quot;<"), std::string::npos);
  // Every '&' starts an entity.
  for (std::size_t at = svg.find('&'); at != std::string::npos; at = svg.find('&', at + 1))
    EXPECT_TRUE(svg.compare(at, 4, "&lt;") == 0 || svg.compare(at, 4, "&gt;") == 0 ||
                svg.compare(at, 5, "&amp;") == 0 || svg.compare(at, 6, "&quot;") == 0 ||
                svg.compare(at, 6, "&apos;") == 0)
        << svg.substr(at, 10);
}

// The number in `attribute="..."` at or after `from`.
double Attribute(const std::string& svg, const std::string& attribute, std::size_t from) {
  const std::size_t at = svg.find(attribute + "=\"", from);
  return at == std::string::npos ? std::nan("") : std::strtod(svg.c_str() + at + attribute.size() + 2, nullptr);
}

// A legend on the data hides it: every legend starts right of the frame of its panel, inside the picture.
TEST(WriteSvg, LegendsStandRightOfTheDataInsideThePicture) {
  const Figure figure{"", "time [s]",
                      {Panel{"speed [rpm]", {Sine("top_rpm", 200, 1), Sine("a much longer legend entry", 200, 2)}},
                       Panel{"torque [N m]", {Sine("bit_torque_Nm", 50, 1e4)}}}};
  const std::string svg = Svg(figure);
  const std::size_t frame = svg.find("fill=\"none\" stroke=\"#444\"");
  ASSERT_NE(frame, std::string::npos);
  const std::size_t frame_tag = svg.rfind("<rect", frame);
  const double data_right = Attribute(svg, "x", frame_tag) + Attribute(svg, "width", frame_tag);
  const double picture_width = Attribute(svg, "width", 0);
  EXPECT_EQ(Count(svg, "<g class=\"legend\">"), 2u);
  for (std::size_t at = svg.find("<g class=\"legend\">"); at != std::string::npos;
       at = svg.find("<g class=\"legend\">", at + 1)) {
    const double left = Attribute(svg, "x", at), width = Attribute(svg, "width", at);
    EXPECT_GT(left, data_right) << svg.substr(at, 200);
    EXPECT_LE(left + width, picture_width);
  }
}

TEST(WriteSvg, SpansAreShadedInEveryPanelAndLabelledOnce) {
  Figure figure{"", "time [s]", {Panel{"a", {Sine("a", 100, 1)}}, Panel{"b", {Sine("b", 100, 1)}}}};
  figure.spans = {{"fit window", 1, 5}, {"held out", 5, 9.9}, {"beyond the data", 20, 30}};
  const std::string svg = Svg(figure);
  EXPECT_EQ(Count(svg, "<rect class=\"span\""), 4u);  // two spans in two panels; the third lies past the data
  EXPECT_EQ(Count(svg, ">fit window<"), 1u);
  EXPECT_EQ(Count(svg, ">held out<"), 1u);
  // The fit window begins at x = 1 of [0, 9.9]: 1/9.9 of the data area's width right of its left edge.
  const std::size_t span = svg.find("<rect class=\"span\"");
  const double x = Attribute(svg, "x", span), width = Attribute(svg, "width", span);
  EXPECT_NEAR(x, 80 + 900 / 9.9, 0.01);
  EXPECT_NEAR(width, 900 * 4 / 9.9, 0.02);
}

// Samples set apart from a line (masked as artefacts) are dots of their own colour, in the legend too, and take no
// colour of the palette from the lines after them.
TEST(WriteSvg, DotsAreCirclesApartFromTheLinesInAColourOfTheirOwn) {
  Series masked{"masked (artefact)", {2, 2.1, 5}, {40, 41, -30}, Mark::kDots, "#9a9a9a"};
  const std::string svg =
      Svg(Figure{"", "time [s]", {Panel{"v", {Sine("recording", 100, 1), masked, Sine("model", 100, 2)}}}});
  EXPECT_EQ(Count(svg, "<polyline"), 2u);
  const std::size_t dots = svg.find("<g class=\"dots\" fill=\"#9a9a9a\">");
  ASSERT_NE(dots, std::string::npos);
  EXPECT_EQ(Count(svg.substr(dots, svg.find("</g>", dots) - dots), "<circle"), 3u);
  EXPECT_NE(svg.find("stroke=\"#1f77b4\""), std::string::npos);  // the recording, first of the palette
  EXPECT_NE(svg.find("stroke=\"#d62728\""), std::string::npos);  // the model, second
  const std::size_t legend = svg.find("<g class=\"legend\">");
  ASSERT_NE(legend, std::string::npos);
  const std::size_t entry = svg.find(">masked (artefact)<", legend);
  ASSERT_NE(entry, std::string::npos);
  const std::size_t key = svg.rfind("<circle", entry);  // a dot, not a line, stands for them
  EXPECT_TRUE(key != std::string::npos && key > legend);
  EXPECT_NE(svg.find(">40<"), std::string::npos);  // the dots count for the y axis: they are data
}

// A zoom on a few cycles: its x axis spans only its own series, with its tick labels and label under it; the panels
// above keep the shared axis (labelled under the last of them) and its spans.
TEST(WriteSvg, APanelWithAnXAxisOfItsOwnSpansItsSeriesOnly) {
  Series zoomed = Sine("zoomed", 100, 1);
  zoomed.x.erase(zoomed.x.begin(), zoomed.x.begin() + 80), zoomed.y.erase(zoomed.y.begin(), zoomed.y.begin() + 80);
  Figure figure{"", "time [s]", {Panel{"a [m]", {Sine("a", 100, 1)}}, Panel{"b [m]", {Sine("b", 100, 1)}}}};
  figure.panels.push_back(Panel{"a [m]", {zoomed}, "time [s], zoomed on the last two"});
  figure.spans = {{"held out", 5, 9.9}};
  const std::string svg = Svg(figure);
  EXPECT_EQ(Count(svg, "<rect class=\"span\""), 2u);  // in the panels on the shared axis only
  EXPECT_EQ(Count(svg, ">time [s]<"), 1u);
  EXPECT_EQ(Count(svg, ">time [s], zoomed on the last two<"), 1u);
  const auto points = PolylinePoints(svg);
  ASSERT_EQ(points.size(), 2u * 100 + 20);
  // The zoom's 20 points, x in [8, 9.9], fill the data area's width (on the shared axis: its right fifth).
  EXPECT_NEAR(points[200].first, 80, 0.01);
  EXPECT_NEAR(points.back().first, 80 + 900, 0.01);
  EXPECT_NE(svg.find(">9.8<"), std::string::npos);  // its tick labels, finer than the shared axis's
  // Room for the shared axis's labels under the second panel, and for the zoom's under it.
  const std::size_t zoom_frame = svg.rfind("<rect", svg.rfind("fill=\"none\" stroke=\"#444\""));
  const double zoom_top = Attribute(svg, "y", zoom_frame);
  EXPECT_GE(zoom_top, 40 + 2 * 220 + 16 + 50);
  EXPECT_NEAR(Attribute(svg, "height", 0), zoom_top + 220 + 50, 0.01);
}

TEST(WriteHeatMapSvg, TheLegendsLongestLabelFitsInThePicture) {
  HeatMap map;
  map.x = {1, 2};
  map.y = {1, 2};
  map.colours = {"#fff", "#fff", "#fff", "#fff"};
  const std::string label = "stable (darker: faster decay), a label longer than the old fixed column";
  map.legend = {{label, "#0a0"}};
  std::ostringstream out;
  WriteHeatMapSvg(map, out);
  const std::string svg = out.str();
  const std::size_t text = svg.find(">" + label + "<");
  ASSERT_NE(text, std::string::npos);
  const double text_x = Attribute(svg, "x", svg.rfind("<text", text));
  EXPECT_LE(text_x + 7 * static_cast<double>(label.size()), Attribute(svg, "width", 0));
}

TEST(WriteSvg, NaNBreaksTheLine) {
  Series s = Sine("gappy", 100, 1);
  s.y[0] = std::nan("");   // a leading gap starts no extra line
  s.y[40] = std::nan("");  // an inner gap does
  s.y[41] = std::nan("");
  s.x[70] = std::nan("");
  EXPECT_EQ(Count(Svg(Figure{"", "", {Panel{"", {s}}}}), "<polyline"), 3u);
}

TEST(WriteSvg, DegenerateInputsGiveFiniteCoordinates) {
  Series constant{"c", {0, 1, 2}, {5, 5, 5}};
  Series empty{"e", {}, {}};
  Series lone{"one point", {1}, {2}};
  const std::string svg = Svg(Figure{"", "", {Panel{"", {constant, empty, lone}}, Panel{"", {}}}});
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_EQ(Count(svg, "<polyline"), 1u);
  EXPECT_EQ(Count(svg, "<circle"), 1u);
  EXPECT_EQ(Svg(Figure{}).rfind("<svg", 0), 0u);
}

TEST(WriteSvg, SpikesSurviveDecimationOfAMillionPoints) {
  Series s{"spiky", {}, {}};
  constexpr int kPoints = 1000000;
  s.x.reserve(kPoints);
  s.y.reserve(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    s.x.push_back(i * 1e-3);
    s.y.push_back(i == 500003 ? 100.0 : (i == 700001 ? -50.0 : std::sin(i * 1e-3)));
  }
  const std::string svg = Svg(Figure{"", "time [s]", {Panel{"v", {s}}}});
  EXPECT_EQ(Count(svg, "<polyline"), 1u);
  const auto points = PolylinePoints(svg);
  EXPECT_LE(points.size(), 4000u);
  EXPECT_LT(svg.size(), 100000u);
  // The axis spans [-50, 100]; the sine alone would cover 2/150 of the panel height, a few pixels.
  double y_min = 1e9, y_max = -1e9;
  for (const auto& p : points) y_min = std::min(y_min, p.second), y_max = std::max(y_max, p.second);
  EXPECT_GT(y_max - y_min, 150.0);
  EXPECT_NE(svg.find(">100<"), std::string::npos);
  EXPECT_NE(svg.find(">-50<"), std::string::npos);
}

TEST(DecimateMinMax, KeepsGlobalExtremesOfASpikySignal) {
  constexpr std::size_t kPoints = 1000000;
  std::vector<double> x(kPoints), y(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    x[i] = 1e-3 * static_cast<double>(i);
    y[i] = std::sin(x[i]) + (i % 9973 == 17 ? 1e-3 * static_cast<double>(i % 7) : 0.0);
  }
  const std::size_t high = 333337, low = 812343;  // one-sample spikes
  y[high] = 42;
  y[low] = -17;
  const std::vector<std::size_t> kept = DecimateMinMax(x, y, x.front(), x.back(), 900);
  EXPECT_LE(kept.size(), 4 * 900u + 4);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), high));
  EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), low));
  EXPECT_EQ(kept.front(), 0u);
  EXPECT_EQ(kept.back(), kPoints - 1);
}

TEST(DecimateMinMax, KeepsShortSeriesWhole) {
  const std::vector<double> x{0, 1, 2, 3}, y{3, 1, 4, 1};
  EXPECT_EQ(DecimateMinMax(x, y, 0, 3, 900), (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(DecimateMinMax, KeepsOneMarkerPerGap) {
  const double nan = std::nan("");
  const std::vector<double> x{0, 1, 2, 3, 4, 5}, y{1, nan, nan, 2, nan, 3};
  EXPECT_EQ(DecimateMinMax(x, y, 0, 5, 900), (std::vector<std::size_t>{0, 1, 3, 4, 5}));
}

TEST(NiceTicks, StepsOfOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_EQ(NiceTicks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(NiceTicks(-57.5, 107.5, 5), (std::vector<double>{-50, 0, 50, 100}));
  const std::vector<double> tenths = NiceTicks(0.05, 0.42, 4);
  ASSERT_EQ(tenths.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(tenths[k], 0.1 * static_cast<double>(k + 1), 1e-15);
  for (double span : {3e-7, 0.013, 1.0, 7.7, 420.0, 9.9e5}) {
    const std::vector<double> ticks = NiceTicks(-0.3 * span, span, 6);
    ASSERT_GE(ticks.size(), 3u) << span;
    ASSERT_LE(ticks.size(), 15u) << span;
    const double step = ticks[1] - ticks[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6)
        << "step " << step;
    EXPECT_GE(ticks.front(), -0.3 * span - 1e-9 * span);
    EXPECT_LE(ticks.back(), span + 1e-9 * span);
  }
  EXPECT_TRUE(NiceTicks(1, 1, 5).empty());
  EXPECT_TRUE(NiceTicks(0, std::nan(""), 5).empty());
}

}  // namespace
}  // namespace drillwave::io
