// The plots' contact with gnuplot: every text reaches a script through gnuplot_quote and comes
// out as exactly that text, never as a command (a station name or an output path
// containing ';system('touch X');print(' or a backquoted command would run it); the plot format
// follows the file name; the speed and frontier plot scripts are run by gnuplot without
// creating anything but their output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "output/frontier_io.hpp"
#include "output/gnuplot.hpp"
#include "output/speed_plot.hpp"
#include "temp_dir_test.hpp"

namespace ecorail::output {
namespace {

class GnuplotTest : public ecorail::testing::TempDirTest {
 protected:
  // Strings that run a command if gnuplot evaluates them instead of printing them.
  std::vector<std::string> hostile() const {
    const std::string x = (dir_ / "X").string();
    return {"a';system('touch " + x + "');print('",
            "X';system('touch " + x + "');print('X",
            "`touch " + x + "`",
            "a\";system(\"touch " + x + "\");print(\"",
            "back\\slash \\n '' \"\" @x $y %z",
            "two\nlines"};
  }
  // An output path that runs "touch dir_/X" when pasted into a script unescaped (as
  // --plot "$PWD/a';system('touch X');print('.svg"); its directories are created.
  std::filesystem::path hostile_path(const std::string& ext) const {
    const std::filesystem::path p =
        dir_.string() + "/a';system('touch " + (dir_ / "X").string() + "');print('" + ext;
    std::filesystem::create_directories(p.parent_path());
    return p;
  }
};

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GnuplotQuote, IsOneSingleQuotedLiteralPerLine) {
  EXPECT_EQ(gnuplot_quote("A6"), "'A6'");
  EXPECT_EQ(gnuplot_quote("it's"), "'it'.\"'\".'s'");
  EXPECT_EQ(gnuplot_quote("a\nb"), "'a'.\"\\n\".'b'");
  EXPECT_EQ(gnuplot_quote("`x`"), "'`x`'");  // backquotes are literal in single quotes
  EXPECT_EQ(gnuplot_quote("tab\there"), "'tab here'");
  EXPECT_EQ(gnuplot_quote("50%"), "'50%'");
  EXPECT_EQ(gnuplot_quote_tic_label("50%"), "'50%%'");
}

TEST(GnuplotFormat, FollowsTheFileName) {
  EXPECT_EQ(plot_format_for("a.svg"), PlotFormat::Svg);
  EXPECT_EQ(plot_format_for("a.SVG"), PlotFormat::Svg);
  EXPECT_EQ(plot_format_for("a.png"), PlotFormat::Png);
  EXPECT_EQ(plot_format_for("-"), PlotFormat::Svg);
  EXPECT_FALSE(plot_format_for("a.pdf").has_value());
  EXPECT_FALSE(plot_format_for("outdir").has_value());
  EXPECT_STREQ(gnuplot_terminal_name(PlotFormat::Png), "pngcairo");
  EXPECT_NE(gnuplot_terminal(PlotFormat::Png, 10, 10).find("pngcairo"), std::string::npos);
}

TEST_F(GnuplotTest, QuotedTextComesBackVerbatimAndRunsNothing) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  std::string script;
  const auto strings = hostile();
  const auto out = dir_ / "printed.txt";
  script += "set print " + gnuplot_quote(out.string()) + "\n";
  for (const auto& s : strings) script += "print " + gnuplot_quote(s) + "\n";
  run_gnuplot(script, {});
  std::string expected;
  for (const auto& s : strings) expected += s + "\n";
  EXPECT_EQ(read_file(out), expected);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "X"));
}

TEST_F(GnuplotTest, TruncatedPlotsAreNotComplete) {
  const auto svg = dir_ / "a.svg";
  std::ofstream(svg) << "<svg>\n<path d='M0 0'/>\n</svg>\n\n";
  EXPECT_NO_THROW(check_plot_complete(svg, PlotFormat::Svg));
  std::ofstream(svg) << "<svg>\n<path d='M0 ";  // cut off, as on a full disk
  EXPECT_THROW(check_plot_complete(svg, PlotFormat::Svg), std::runtime_error);
  EXPECT_THROW(check_plot_complete(dir_ / "missing.svg", PlotFormat::Svg), std::runtime_error);
  const auto png = dir_ / "a.png";
  const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  std::ofstream(png, std::ios::binary) << "\x89PNG\r\n\x1a\n...." << iend;
  EXPECT_NO_THROW(check_plot_complete(png, PlotFormat::Png));
  std::ofstream(png, std::ios::binary) << "\x89PNG\r\n\x1a\n....";
  EXPECT_THROW(check_plot_complete(png, PlotFormat::Png), std::runtime_error);
}

TEST_F(GnuplotTest, FailureIsOneLineWithGnuplotsMessage) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  try {
    run_gnuplot("this is not gnuplot\n", {});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnuplot failed"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST_F(GnuplotTest, SvgAndPngTerminalsAreKnown) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  EXPECT_TRUE(gnuplot_supports(PlotFormat::Svg));
  EXPECT_EQ(gnuplot_problem(PlotFormat::Svg), "");
}

// A two-section journey: depart, run, stop at a station, dwell, run, stop.
Timeline journey() {
  Timeline t;
  double time = 0.0, s = 0.0;
  auto run = [&](int section) {
    for (int k = 0; k <= 100; ++k) {
      TimelinePoint p;
      p.section = section;
      // Speed up and down over 1000 m.
      const double x = k / 100.0;
      p.s_m = s + 1000.0 * x;
      p.v_ms = 20.0 * std::sin(3.14159265358979 * x);
      if (k == 100) p.v_ms = 0.0;
      p.t_s = time + 80.0 * x;
      p.speed_limit_ms = 22.2;
      p.regime = x < 0.3   ? physics::Regime::FullTraction
                 : x < 0.8 ? physics::Regime::Coast
                           : physics::Regime::FullBrake;
      t.push_back(p);
    }
    // The last samples of a braking run lie a few millimetres apart, the final one at 0.
    for (int k = 1; k <= 3; ++k) {
      TimelinePoint p = t.back();
      p.s_m += 0.001 * k;
      p.t_s += 0.1 * k;
      p.v_ms = k < 3 ? 0.3 / k : 0.0;
      t.push_back(p);
    }
    s = t.back().s_m;
    time = t.back().t_s;
  };
  run(0);
  for (int k = 1; k <= 30; ++k) {  // dwell
    TimelinePoint p = t.back();
    p.t_s += 1.0;
    p.v_ms = 0.0;
    p.dwelling = true;
    t.push_back(p);
  }
  time = t.back().t_s;
  run(1);
  return t;
}

TEST(SpeedPlotRows, EveryStopIsDrawnAtZero) {
  for (const PlotAxis axis : {PlotAxis::Distance, PlotAxis::Time}) {
    const Timeline t = journey();
    const auto rows = speed_plot_rows(t, axis);
    // The last row before the dwell and the last row of all are standstills.
    bool seen_dwell = false;
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
      if (!rows[i].dwelling && rows[i + 1].dwelling && !seen_dwell) {
        EXPECT_EQ(rows[i].speed_kmh, 0.0) << "first stop drawn at " << rows[i].speed_kmh;
        seen_dwell = true;
      }
    }
    EXPECT_TRUE(seen_dwell);
    EXPECT_EQ(rows.back().speed_kmh, 0.0);
  }
}

TEST(SpeedPlotRows, HighestLimitIsBelowTheFrame) {
  const auto rows = speed_plot_rows(journey(), PlotAxis::Distance);
  double top = 0.0;
  for (const auto& r : rows) top = std::max({top, r.limit_kmh, r.speed_kmh});
  EXPECT_GE(speed_axis_max_kmh(rows), top * 1.1);
}

TEST(SpeedPlotScript, StationsNamedMarkedAndObjectiveStated) {
  const Timeline t = journey();
  SpeedPlotLabels labels;
  labels.stations = {"A6", "A7", "A8"};
  labels.objective = "least traction energy";
  const auto rows = speed_plot_rows(t, PlotAxis::Distance);
  const auto marks = station_marks(t, labels.stations, PlotAxis::Distance);
  ASSERT_EQ(marks.size(), 3u);
  EXPECT_EQ(marks[1].name, "A7");
  EXPECT_NEAR(marks[1].arrive_x, 1000.006, 1e-6);  // where the train came to rest
  EXPECT_NEAR(marks[1].depart_x, marks[1].arrive_x, 1e-9);
  const std::string gp = speed_plot_script(rows, marks, "run", labels, PlotFormat::Svg, "/x.svg");
  for (const char* needle : {"'A6'", "'A7'", "'A8'", "least traction energy", "'full traction'",
                             "'coast'", "'full brake'", "'speed limit'"}) {
    EXPECT_NE(gp.find(needle), std::string::npos) << needle;
  }
  // The key is placed where gnuplot keeps it (a key "at" a screen position that does not fit
  // is silently dropped).
  EXPECT_EQ(gp.find("set key at screen"), std::string::npos);
}

TEST_F(GnuplotTest, HostileStationNamesAndPathsRunNothing) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  const Timeline t = journey();
  for (const auto& name : hostile()) {
    SpeedPlotLabels labels;
    labels.stations = {"A6", name, "A8"};
    labels.objective = name;
    const auto file = dir_ / "text.svg";
    write_speed_plot_file(file, t, name, labels, PlotFormat::Svg);
    EXPECT_NE(read_file(file).find("A8"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir_ / "X")) << name;
  }
  for (const PlotFormat format : {PlotFormat::Svg, PlotFormat::Png}) {
    if (!gnuplot_supports(format)) continue;
    const auto file = hostile_path(format == PlotFormat::Png ? ".png" : ".svg");
    write_speed_plot_file(file, t, "run", {}, format);
    EXPECT_TRUE(std::filesystem::exists(file));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "X"));
  }
}

TEST_F(GnuplotTest, HostileFrontierLabelsAndPathRunNothing) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  std::vector<LabelledFrontier> frontiers;
  for (const auto& name : hostile()) {
    LabelledFrontier lf;
    lf.from = "A6";
    lf.to = name;
    for (int k = 0; k < 3; ++k) {
      dp::FrontierPoint p;
      p.target_time_s = p.running_time_s = 90.0 + 10.0 * k;
      p.cost_J = 4e7 - 5e6 * k;
      lf.frontier.points.push_back(p);
    }
    frontiers.push_back(lf);
  }
  const auto file = hostile_path(".svg");
  write_frontiers_plot_file(file, frontiers, hostile()[0], hostile()[2], PlotFormat::Svg);
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "X"));
}

TEST(FrontierCurveStyle, ThirteenCurvesAllDistinct) {
  // frontier --all draws the 13 sections of the reference line.
  for (std::size_t i = 0; i < 13; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const CurveStyle a = frontier_curve_style(i), b = frontier_curve_style(j);
      EXPECT_FALSE(a.colour == b.colour && a.dash_type == b.dash_type)
          << "curves " << i << " and " << j << " look alike";
    }
  }
}

}  // namespace
}  // namespace ecorail::output
