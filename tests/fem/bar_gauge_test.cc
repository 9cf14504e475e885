// The bars' strain over a gauge length (fem/bar_gauge.h) against closed forms: a cantilever's
// linear strain profile, and a plastic elongation localised in the lowest row of cells, whose
// point strain grows as the row shrinks while the gauge's mean stays that of the hinge.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <stdexcept>
#include <vector>

#include "fem/bar_gauge.h"

namespace
{
  using namespace kimp::fem;

  /// A wall of height `height` in rows of cells of height `h`, `columns` vertical lines of Gauss
  /// points at x = 0.01, 0.02, ...: two segments per cell and line (the 2-point Gauss column's
  /// halves), bottom to top within each line.
  std::vector<GaugeSegment> wall_segments(double height, double h, int columns)
  {
    std::vector<GaugeSegment> s;
    const int                 rows = static_cast<int>(std::lround(height / h));
    for (int c = 0; c < columns; ++c)
      for (int r = 0; r < rows; ++r)
      {
        s.push_back({0.01 * (c + 1), r * h, (r + 0.5) * h});
        s.push_back({0.01 * (c + 1), (r + 0.5) * h, (r + 1) * h});
      }
    return s;
  }

  /// The strain of each segment: `field` at the segment's midpoint.
  template <class F>
  std::vector<double> sample(const std::vector<GaugeSegment> &segments, F field)
  {
    std::vector<double> e;
    for (const GaugeSegment &g : segments)
      e.push_back(field(g.x, 0.5 * (g.y_lo + g.y_hi)));
    return e;
  }
} // namespace

// A cantilever of height H under a tip load: the bar strain falls linearly from the base,
// eps(y) = kappa (H - y) on the tension face (x = 0.01), the opposite on the compression face.
// Over a gauge of length L from the base its mean is kappa (H - L / 2), centred at L / 2, on
// every mesh whose cells tile L (the midpoint sample integrates a linear field exactly).
TEST(BarGauge, LinearStrainProfileOfACantileverIsAveragedExactly)
{
  const double H = 1.25, kappa = 2e-3, L = 0.125;
  for (const double h : {0.05, 0.025, 0.0125})
  {
    const auto segments = wall_segments(H, h, 2);
    const auto strain =
      sample(segments,
             [&](double x, double y) { return (x < 0.015 ? 1.0 : -0.5) * kappa * (H - y); });
    const BarGauge    gauge(segments, L);
    const GaugeStrain g = gauge.largest_mean(strain);
    std::printf("h = %.4g m: gauge mean %.6g (closed form %.6g) centred at %.4g m\n",
                h,
                g.strain,
                kappa * (H - 0.5 * L),
                g.centre);
    EXPECT_NEAR(g.strain, kappa * (H - 0.5 * L), 1e-12);
    EXPECT_NEAR(g.centre, 0.5 * L, 1e-12);
  }
}

// A hinge: the elastic strain eps_e everywhere plus a plastic elongation delta concentrated in
// the lowest row of cells (height h), as perfectly bonded smeared bars localise it. The largest
// point strain is eps_e + delta / h and doubles as h halves; the gauge's mean is
// eps_e + delta / L on every mesh whose row is within the gauge.
TEST(BarGauge, LocalisedPlasticElongationReadsTheSameOnEveryMesh)
{
  const double H = 1.25, eps_e = 2.5e-3, delta = 1e-3, L = 0.125;
  double       previous_point = 0;
  for (const double h : {0.05, 0.025, 0.0125})
  {
    const auto segments = wall_segments(H, h, 3);
    const auto strain =
      sample(segments, [&](double, double y) { return eps_e + (y < h ? delta / h : 0.0); });
    double point = 0;
    for (const double e : strain)
      point = std::max(point, e);
    const GaugeStrain g = BarGauge(segments, L).largest_mean(strain);
    std::printf("h = %.4g m: point strain %.6g, gauge mean %.6g (closed form %.6g)\n",
                h,
                point,
                g.strain,
                eps_e + delta / L);
    EXPECT_NEAR(point, eps_e + delta / h, 1e-12);
    EXPECT_NEAR(g.strain, eps_e + delta / L, 1e-12);
    EXPECT_LE(g.centre, 0.5 * L + h) << "the gauge holds the hinge at the base";
    if (previous_point > 0)
    {
      EXPECT_GT(point / previous_point, 1.6) << "the point strain grows as the row shrinks";
    }
    previous_point = point;
  }
}

// A band above the base: the largest mean is over any gauge that holds the whole band.
// Compression reads as its magnitude. A line shorter than the gauge is read over its length.
TEST(BarGauge, BandAboveTheBaseCompressionAndShortLines)
{
  const double h = 0.025, L = 0.1, delta = 5e-4;
  const auto   segments = wall_segments(1.0, h, 1);
  const auto   strain =
    sample(segments, [&](double, double y) { return y > 0.5 && y < 0.5 + h ? -delta / h : 0.0; });
  const GaugeStrain g = BarGauge(segments, L).largest_mean(strain);
  EXPECT_NEAR(g.strain, delta / L, 1e-12);
  EXPECT_GE(g.centre, 0.5 + h - 0.5 * L - 1e-12);
  EXPECT_LE(g.centre, 0.5 + 0.5 * L + 1e-12);

  const auto        short_line = wall_segments(0.05, h, 1);
  const GaugeStrain s =
    BarGauge(short_line, L).largest_mean(std::vector<double>{1e-3, 1e-3, 3e-3, 3e-3});
  EXPECT_NEAR(s.strain, 2e-3, 1e-12);
  EXPECT_NEAR(s.centre, 0.025, 1e-12);
}

TEST(BarGauge, RefusesANonPositiveLengthAnEmptySegmentOrAWrongStrainCount)
{
  const auto segments = wall_segments(0.1, 0.05, 1);
  EXPECT_THROW(BarGauge(segments, 0.0), std::invalid_argument);
  EXPECT_THROW(BarGauge({{0.0, 0.1, 0.1}}, 0.1), std::invalid_argument);
  EXPECT_THROW(BarGauge(segments, 0.1).largest_mean({1.0}), std::invalid_argument);
}
