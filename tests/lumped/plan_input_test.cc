// Input of the 3D (plan) engine: plan geometry (areas, centroids, polar moments, the moat
// offset), two-component ground motion, and the errors for bad input (a wall polygon that does
// not enclose the slab, a gap <= 0, a self-intersecting polygon, a missing second component).
#include <cmath>
#include <gtest/gtest.h>

#include "lumped/plan/plan_central_difference.h"
#include "tests/lumped/plan_scenes.h"

namespace kimp::lumped::plan
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// The message of the std::invalid_argument `f` throws ("" if none).
    template <class F>
    std::string error_of(F f)
    {
      try
      {
        f();
      }
      catch (const std::invalid_argument &e)
      {
        return e.what();
      }
      return "";
    }

    ::testing::AssertionResult mentions(const std::string &message, const std::string &part)
    {
      if (message.find(part) != std::string::npos)
        return ::testing::AssertionSuccess();
      return ::testing::AssertionFailure()
             << "'" << message << "' does not mention '" << part << "'";
    }
  } // namespace

  TEST(PlanGeometry, PolygonPropertiesMatchClosedForms)
  {
    const Polygon r = rectangle(20.0, 12.0, Point(3.0, -1.0));
    EXPECT_DOUBLE_EQ(signed_area(r), 240.0);
    EXPECT_NEAR((centroid(r) - Point(3.0, -1.0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(polar_moment(r, Point(3.0, -1.0)), 240.0 * (400.0 + 144.0) / 12.0, 1e-9);
    // L-shape: two rectangles; parallel axes.
    const Polygon l =
      {Point(0, 0), Point(10, 0), Point(10, 4), Point(4, 4), Point(4, 10), Point(0, 10)};
    const double a1 = 40.0, a2 = 24.0; // 10×4 and 4×6
    const Point  c1(5.0, 2.0), c2(2.0, 7.0);
    const Point  c = (a1 * c1 + a2 * c2) / (a1 + a2);
    EXPECT_NEAR((centroid(l) - c).norm(), 0.0, 1e-12);
    const double j = a1 * (100.0 + 16.0) / 12.0 + a1 * (c1 - c).squaredNorm() +
                     a2 * (16.0 + 36.0) / 12.0 + a2 * (c2 - c).squaredNorm();
    EXPECT_NEAR(polar_moment(l, c), j, 1e-9 * j);
    // Orientation does not matter.
    Polygon reversed(l.rbegin(), l.rend());
    EXPECT_NEAR(polar_moment(reversed, c), j, 1e-9 * j);
    EXPECT_DOUBLE_EQ(signed_area(counter_clockwise(reversed)), 64.0);
  }

  TEST(PlanGeometry, MoatIsTheOutlineOffsetByItsGaps)
  {
    const Polygon moat = moat_polygon(rectangle(20.0, 10.0), {0.1, 0.2, 0.3, 0.4});
    // Edges: 0 bottom, 1 right, 2 top, 3 left.
    ASSERT_EQ(moat.size(), 4u);
    EXPECT_NEAR(moat[0].x(), -10.4, 1e-12);
    EXPECT_NEAR(moat[0].y(), -5.1, 1e-12);
    EXPECT_NEAR(moat[1].x(), 10.2, 1e-12);
    EXPECT_NEAR(moat[2].y(), 5.3, 1e-12);
    // Each corner of the slab meets the faces of its two edges at their gaps.
    PlanBuilding b;
    PlanLevel    l;
    l.mass    = 1e6;
    l.outline = rectangle(20.0, 10.0);
    b.levels  = {l};
    b.storeys = {storey(1e8, 1e8, 1e10)};
    PlanMoat m;
    m.wall = moat;
    m.law  = kimp::testing::contact_law("linear", 1e8);
    for (const PlanContact &c : moat_contacts(m, b))
    {
      const double expected = std::vector<double>{0.1, 0.2, 0.3, 0.4}[c.segment];
      EXPECT_NEAR(c.gap, expected, 1e-12) << c.name;
      EXPECT_EQ(c.edge, c.segment) << c.name;
      EXPECT_DOUBLE_EQ(c.weight, 0.5) << c.name;
    }
    EXPECT_EQ(moat_contacts(m, b).size(), 8u);
    m.points_per_edge = 5;
    double weights    = 0.0;
    for (const PlanContact &c : moat_contacts(m, b))
      weights += c.edge == 0 ? c.weight : 0.0;
    EXPECT_NEAR(weights, 1.0, 1e-15);
  }

  TEST(PlanMotion, RotationKeepsTheRecordAndItsOrthogonalCompanion)
  {
    const GroundMotion     g  = kimp::testing::near_fault_motion(6.0);
    const PlanGroundMotion m0 = along_angle(g, 0.0);
    EXPECT_EQ(m0.x, g.acceleration);
    for (const double y : m0.y)
      EXPECT_EQ(y, 0.0);
    SyntheticMotionSpec spec;
    spec.duration             = 5.5;
    spec.seed                 = 5;
    const GroundMotion     g2 = synthetic_near_fault(spec);
    const PlanGroundMotion m  = two_components(g, g2, 40.0 * pi / 180.0);
    ASSERT_EQ(m.x.size(), g.acceleration.size());
    for (std::size_t i = 0; i < m.x.size(); ++i)
    {
      const double a1 = g.acceleration[i], a2 = i < g2.acceleration.size() ? g2.acceleration[i] : 0;
      EXPECT_NEAR(std::hypot(m.x[i], m.y[i]), std::hypot(a1, a2), 1e-12 * (1 + std::abs(a1)));
      // Projection on the first component's direction is that component.
      EXPECT_NEAR(m.x[i] * std::cos(40.0 * pi / 180.0) + m.y[i] * std::sin(40.0 * pi / 180.0),
                  a1,
                  1e-12 * (1 + std::abs(a1)));
    }
  }

  TEST(PlanInput, BadInputIsRefusedWithAClearMessage)
  {
    const PlanBuilding b = kimp::testing::plan_reference_building();
    // A wall polygon that does not enclose the slab.
    PlanMoat moat = kimp::testing::plan_moat(b, "linear", 2.5e9, 0.15);
    moat.wall     = rectangle(20.2, 19.0);
    EXPECT_TRUE(mentions(error_of([&] { validate(moat, b); }), "does not enclose the slab"));
    moat.wall = {Point(-10.5, -10.5),
                 Point(10.5, -10.5),
                 Point(10.5, 10.5),
                 Point(0.0, -5.0),
                 Point(-10.5, 10.5)};
    EXPECT_TRUE(mentions(error_of([&] { validate(moat, b); }), "does not enclose the slab"));
    // A gap <= 0.
    EXPECT_TRUE(mentions(error_of(
                           [&] {
                             moat_around(b, {0.15, 0.0, 0.15, 0.15});
                           }),
                         "gap[1] = 0 m (must be > 0)"));
    EXPECT_TRUE(mentions(error_of([&] { moat_around(b, {-0.1}); }), "must be > 0"));
    EXPECT_TRUE(mentions(error_of([&] { moat_around(b, {0.1, 0.1}); }), "2 gaps for a slab of 4"));
    // A self-intersecting polygon (a bow tie), for the wall and for a slab.
    moat.wall = {Point(-11, -11), Point(11, 11), Point(11, -11), Point(-11, 11)};
    EXPECT_TRUE(mentions(error_of([&] { validate(moat, b); }), "self-intersecting"));
    PlanBuilding bow      = b;
    bow.levels[2].outline = {Point(-10, -10), Point(10, 10), Point(10, -10), Point(-10, 10)};
    EXPECT_TRUE(mentions(error_of([&] { validate(bow); }), "plan.levels[2].outline: edges"));
    // A missing second component, and components of different sampling.
    const GroundMotion g = kimp::testing::near_fault_motion(6.0);
    GroundMotion       empty;
    empty.dt   = g.dt;
    empty.name = "kobe_fp";
    EXPECT_TRUE(mentions(error_of([&] { two_components(g, empty, 0.0); }),
                         "second component of 'synthetic_near_fault' is missing"));
    GroundMotion other = g;
    other.dt           = 2 * g.dt;
    other.name         = "other";
    EXPECT_TRUE(mentions(error_of([&] { two_components(g, other, 0.0); }),
                         "must have the same sampling interval"));
    // Building fields.
    PlanBuilding bad   = b;
    bad.levels[1].mass = -1.0;
    EXPECT_TRUE(mentions(error_of([&] { validate(bad); }), "plan.levels[1].mass = -1 kg"));
    bad = b;
    bad.storeys.pop_back();
    EXPECT_TRUE(mentions(error_of([&] { validate(bad); }), "plan.storeys has 3 entries"));
    bad                            = b;
    bad.storeys[0].elements[0].k_x = -5.0;
    EXPECT_TRUE(mentions(error_of([&] { validate(bad); }), "elements[0].k_x = -5 N/m"));
    // A moat law that cannot be made, and a time step above the stability limit.
    moat         = kimp::testing::plan_moat(b, "linear", 2.5e9, 0.15);
    moat.law.law = "rubber";
    EXPECT_TRUE(
      mentions(error_of([&] { validate(moat, b); }), "moat.law: force law: law = 'rubber'"));
    PlanScene scene;
    scene.building = b;
    scene.moat     = kimp::testing::plan_moat(b, "linear", 2.5e9, 0.15);
    PlanOptions opt;
    opt.dt = 0.05;
    const PlanCentralDifference cdm(PlanModel(scene), opt);
    EXPECT_TRUE(mentions(error_of([&] { cdm.time_step(0.01); }), "exceeds the stability limit"));
  }
} // namespace kimp::lumped::plan

namespace kimp::lumped::plan
{
  TEST(PlanInput, ADirectionWithoutStiffnessIsNamed)
  {
    PlanBuilding b = kimp::testing::plan_reference_building();
    for (PlanStorey &s : b.storeys)
      for (StoreyElement &e : s.elements)
        e.k_y = 0.0;
    b.isolators.clear();
    b.storeys.insert(b.storeys.begin(), storey(600e6, 0.0, 1e10));
    const std::string message = [&]
    {
      try
      {
        plan_damping(b);
      }
      catch (const std::invalid_argument &e)
      {
        return std::string(e.what());
      }
      return std::string();
    }();
    EXPECT_NE(message.find("the Rayleigh damping along y needs stiffness"), std::string::npos)
      << message;
  }
} // namespace kimp::lumped::plan
