// GradedSpacing: exact ends and breakpoints, sizes bounded by the size field, neighbour ratios
// bounded by the grading, a closed-form geometric progression, and argument checks.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/graded_spacing.h"

namespace
{
  using kimp::geometry::GradedSpacing;
  using kimp::geometry::max_neighbour_ratio;

  constexpr double round_off = 1e-12; // relative

  // Regime in which the grading bound holds across breakpoints too (documented in the header).
  constexpr double well_adaptable_grading  = 1.1;
  constexpr double well_separated_elements = 3.0; // in units of h_max
} // namespace


TEST(GradedSpacing, UniformFineZoneGivesCeilOfLengthOverSize)
{
  const GradedSpacing spacing(0.0, 1.0, 0.025, 0.1, 1.15);
  const auto          exact = spacing.nodes(0.8, 1.0);
  EXPECT_EQ(exact.size(), 9u) << "0.2 m / 0.025 m = 8 elements, no extra one from round-off";
  const auto rounded = spacing.nodes(0.0, 0.21);
  ASSERT_EQ(rounded.size(), 10u) << "ceil(0.21 / 0.025) = 9 elements";
  for (std::size_t i = 1; i < rounded.size(); ++i)
    EXPECT_NEAR(rounded[i] - rounded[i - 1], 0.21 / 9, round_off);
}


TEST(GradedSpacing, GradedZoneIsAGeometricProgression)
{
  // From a point fine zone with no cap in reach, ψ(s) = ln(1 + s ln g / h) / ln g, so equal
  // steps c of ψ give sizes in the ratio g^c exactly.
  constexpr double    h = 0.01, g = 1.2;
  const GradedSpacing spacing(0.0, 0.0, h, 1e3, g);
  const double        length = 0.5;
  const auto          nodes  = spacing.nodes(0.0, length);
  const double        psi    = std::log1p(length * std::log(g) / h) / std::log(g);
  const double        n      = std::ceil(psi);
  ASSERT_EQ(nodes.size(), static_cast<std::size_t>(n) + 1);
  const double ratio = std::pow(g, psi / n);
  for (std::size_t i = 2; i < nodes.size(); ++i)
    EXPECT_NEAR((nodes[i] - nodes[i - 1]) / (nodes[i - 1] - nodes[i - 2]), ratio, 1e-9)
      << "element " << i;
}


TEST(GradedSpacing, MetricAndCoordinateAreInverse)
{
  const GradedSpacing spacing(1.0, 1.2, 0.02, 0.1, 1.15);
  for (const double s : {-3.0, 0.0, 0.5, 0.99, 1.0, 1.1, 1.2, 1.3, 2.0, 9.0})
    EXPECT_NEAR(spacing.coordinate(spacing.metric(s)), s, 1e-12 * std::max(1.0, std::abs(s)))
      << "s = " << s;
}


TEST(GradedSpacing, RandomFieldsRespectSizeCapGradingAndBreakpoints)
{
  std::mt19937                           rng(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr int                          n_trials         = 400;
  int                                    n_well_separated = 0;
  for (int trial = 0; trial < n_trials; ++trial)
  {
    const double        h_fine  = 0.005 + 0.05 * unit(rng);
    const double        h_max   = h_fine * (1.0 + 10.0 * unit(rng));
    const double        grading = 1.0 + 0.5 * unit(rng);
    const double        a       = 3.0 * unit(rng);
    const double        b       = a + 0.5 * unit(rng);
    const double        begin   = -1.0 + unit(rng);
    const double        end     = begin + 0.05 + 4.0 * unit(rng);
    std::vector<double> breakpoints;
    for (int k = 0; k < 3; ++k)
      breakpoints.push_back(begin + (end - begin) * unit(rng));

    const GradedSpacing spacing(a, b, h_fine, h_max, grading);
    const auto          nodes = spacing.nodes(begin, end, breakpoints);
    SCOPED_TRACE(::testing::Message()
                 << "trial " << trial << ": h_fine " << h_fine << ", h_max " << h_max
                 << ", grading " << grading << ", fine zone [" << a << ", " << b << "], axis ["
                 << begin << ", " << end << "], breakpoints " << breakpoints[0] << ' '
                 << breakpoints[1] << ' ' << breakpoints[2]);

    EXPECT_EQ(nodes.front(), begin);
    EXPECT_EQ(nodes.back(), end);
    for (const double p : breakpoints)
      EXPECT_TRUE(std::find(nodes.begin(), nodes.end(), p) != nodes.end()) << "breakpoint " << p;
    for (std::size_t i = 1; i < nodes.size(); ++i)
    {
      const double size = nodes[i] - nodes[i - 1];
      ASSERT_GT(size, 0.0);
      const double field = std::max(spacing.size_at(nodes[i - 1]), spacing.size_at(nodes[i]));
      EXPECT_LE(size, field * (1 + round_off)) << "element " << i;
      EXPECT_LE(size, h_max * (1 + round_off)) << "element " << i;
    }

    // Within a span (no breakpoint between two neighbours) the grading always holds.
    for (std::size_t i = 2; i < nodes.size(); ++i)
    {
      if (std::find(breakpoints.begin(), breakpoints.end(), nodes[i - 1]) != breakpoints.end())
        continue;
      const double left  = nodes[i - 1] - nodes[i - 2];
      const double right = nodes[i] - nodes[i - 1];
      EXPECT_LE(std::max(left / right, right / left), grading * (1 + round_off))
        << "elements " << i - 1 << ", " << i;
    }

    // Across breakpoints it holds too when they are a few elements apart and the grading
    // leaves room to adapt (the scene's case); closer or with grading near 1 it is best effort.
    std::vector<double> cuts = breakpoints;
    cuts.push_back(begin);
    cuts.push_back(end);
    std::sort(cuts.begin(), cuts.end());
    double separation = HUGE_VAL;
    for (std::size_t k = 1; k < cuts.size(); ++k)
      separation = std::min(separation, cuts[k] - cuts[k - 1]);
    if (grading >= well_adaptable_grading && separation >= well_separated_elements * h_max)
    {
      ++n_well_separated;
      EXPECT_LE(max_neighbour_ratio(nodes), grading * (1 + round_off));
    }
  }
  EXPECT_GE(n_well_separated, 10) << "too few trials exercised the across-breakpoint bound";
}


TEST(GradedSpacing, RefusesBadArguments)
{
  EXPECT_THROW(GradedSpacing(0.0, 1.0, 0.0, 0.1, 1.1), std::invalid_argument);
  EXPECT_THROW(GradedSpacing(0.0, 1.0, 0.2, 0.1, 1.1), std::invalid_argument);
  EXPECT_THROW(GradedSpacing(0.0, 1.0, 0.01, 0.1, 0.9), std::invalid_argument);
  EXPECT_THROW(GradedSpacing(1.0, 0.0, 0.01, 0.1, 1.1), std::invalid_argument);
  const GradedSpacing spacing(0.0, 0.0, 0.01, 0.1, 1.1);
  EXPECT_THROW(spacing.nodes(1.0, 1.0), std::invalid_argument);
}
