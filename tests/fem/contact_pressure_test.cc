// Physics tests of the contact pressure of the deformed-mesh frames (fem::ImpactFrames): its
// integral over the contact face equals the contact force history at every frame, and two equal
// bars press on each other with the closed-form pressure rho c v / 2 across the whole face.
#include <gtest/gtest.h>
#include <iostream>

#include "tests/fem/impact_test_support.h"

namespace
{
  using namespace kimp::fem;
  using namespace kimp::fem::testing;

  /** Contact force of the history sample at exactly time t (frames and samples share t = n dt). */
  double history_force_at(const ImpactResult &r, double t)
  {
    const auto &h = r.history;
    for (std::size_t i = 0; i < h.time.size(); ++i)
      if (h.time[i] == t)
        return h.contact_force[i];
    ADD_FAILURE() << "no history sample at t = " << t << " s";
    return 0;
  }

  /** Integral of the contact pressure of frame j over the face, sum_i p_i l_i (N/m). */
  double nodal_integral(const ImpactFrames &f, std::size_t j)
  {
    const std::size_t n   = f.contact_vertices.size();
    double            sum = 0;
    for (std::size_t i = 0; i < n; ++i)
      sum += f.contact_pressure[j * n + i] * f.contact_length[i];
    return sum;
  }

  TEST(ContactPressure, IntegratesToTheContactForceAtEveryFrame)
  {
    // The pressure is each node's penalty force over its tributary length, so summing p_i l_i
    // gives the history's force up to the order of the sum: round-off, measured < 1e-15 of the
    // peak force; 1e-12 leaves margin. With an elastic slab the contact nodes are the slab
    // front, whose tributary lengths are half of each neighbouring face: then the trapezoid rule
    // over the face polyline (from the frame's vertices, not from contact_length) is the same
    // sum, so it must agree to the same round-off.
    constexpr double round_off = 1e-12;
    for (const auto &[rigid, implicit] : {std::pair{true, false}, {false, false}, {true, true}})
    {
      auto p     = scene_parameters(0.05, rigid, rigid ? "pressure_rigid.msh" : "pressure.msh");
      p.end_time = 0.004;
      p.output_interval = 0; // every step, so every frame's time is a history sample
      p.frame_interval  = 0.1e-3;
      if (implicit)
        p.integrator = ImpactParameters::Integrator::implicit_newmark;
      const auto r = run_impact(p, MPI_COMM_WORLD, nullptr);
      if (rank() != 0)
        continue;
      const ImpactFrames &f = r.frames;
      const std::size_t   n = f.contact_vertices.size();
      ASSERT_GT(n, 1u);
      ASSERT_EQ(f.contact_length.size(), n);
      ASSERT_EQ(f.contact_pressure.size(), f.time.size() * n);
      double face = 0;
      for (const double l : f.contact_length)
        face += l;
      // The face the pressure acts on: the slab's thickness against a rigid slab, the slab
      // front's length (first to last node along y) with an elastic slab.
      const auto y_of = [&](std::size_t i)
      { return f.vertices[2 * static_cast<std::size_t>(f.contact_vertices[i]) + 1]; };
      const double width = rigid ? p.slab_face_y1 - p.slab_face_y0 : y_of(n - 1) - y_of(0);
      EXPECT_NEAR(face, width, round_off * width) << (rigid ? "rigid" : "elastic") << " slab";

      double peak = 0, worst = 0, worst_trapezoid = 0;
      for (const double x : r.history.contact_force)
        peak = std::max(peak, x);
      ASSERT_GT(peak, 0);
      std::size_t in_contact = 0;
      for (std::size_t j = 0; j < f.time.size(); ++j)
      {
        const double force = history_force_at(r, f.time[j]);
        in_contact += force > 0 ? 1 : 0;
        for (std::size_t i = 0; i < n; ++i)
          EXPECT_GE(f.contact_pressure[j * n + i], 0.0) << "compression positive, never a pull";
        const double integral = nodal_integral(f, j);
        worst                 = std::max(worst, std::abs(integral - force) / peak);
        EXPECT_NEAR(integral, force, round_off * peak) << "frame " << j << ", t = " << f.time[j];
        if (!rigid)
        {
          double trapezoid = 0;
          for (std::size_t i = 0; i + 1 < n; ++i)
            trapezoid += 0.5 * (f.contact_pressure[j * n + i] + f.contact_pressure[j * n + i + 1]) *
                         (y_of(i + 1) - y_of(i));
          worst_trapezoid = std::max(worst_trapezoid, std::abs(trapezoid - force) / peak);
          EXPECT_NEAR(trapezoid, force, round_off * peak) << "frame " << j;
        }
      }
      EXPECT_GT(in_contact, 3u) << "frames during the contact";
      std::cout << (rigid ? "rigid" : "elastic") << " slab, "
                << (implicit ? "implicit" : "explicit") << ": " << f.time.size() << " frames ("
                << in_contact << " in contact), " << n << " contact nodes over " << face
                << " m, max |sum p l - F| / F_peak = " << worst
                << ", trapezoid over the face = " << worst_trapezoid << '\n';
    }
  }

  TEST(ContactPressure, TwoEqualBarsPressIsHalfImpedanceTimesVelocityOverTheFace)
  {
    // 1D wave (nu = 0): while the waves run (2 L / c), the interface stress is rho c v / 2,
    // uniform over the face. The penalty contact and the explicit step make the nodal pressure
    // ring around it; averaged over the middle of the contact each node and the face are within
    // 1e-3 of it (measured 7e-6: the 1D wave loads the face uniformly).
    constexpr double tolerance = 1e-3;
    const double     L = 1.0, t = 0.1, v = 1.0;
    auto             p = bar_parameters(write_two_bars(L, t, 1e-4, 8, "pressure_bars.msh"));
    p.frame_interval   = 2e-6;
    const auto r       = run_impact(p, MPI_COMM_WORLD, nullptr);
    if (rank() != 0)
      return;
    const ImpactFrames &f = r.frames;
    const std::size_t   n = f.contact_vertices.size();
    ASSERT_EQ(n, 9u) << "8 cells across the face: 9 nodes";
    const double        c        = std::sqrt(bar_material.youngs_modulus / bar_material.density);
    const double        expected = bar_material.density * c * v / 2;
    const double        t0 = r.summary.contact_start, T = r.summary.contact_duration;
    std::vector<double> mean(n, 0.0);
    std::size_t         count = 0;
    for (std::size_t j = 0; j < f.time.size(); ++j)
      if (f.time[j] >= t0 + 0.2 * T && f.time[j] <= t0 + 0.8 * T)
      {
        for (std::size_t i = 0; i < n; ++i)
          mean[i] += f.contact_pressure[j * n + i];
        ++count;
      }
    ASSERT_GT(count, 20u);
    double face = 0, length = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      mean[i] /= static_cast<double>(count);
      EXPECT_NEAR(mean[i] / expected, 1.0, tolerance) << "node " << i;
      face += mean[i] * f.contact_length[i];
      length += f.contact_length[i];
    }
    EXPECT_NEAR(length, t, 1e-12 * t);
    EXPECT_NEAR(face / length / expected, 1.0, tolerance);
    std::cout << "bars: mean pressure over the face " << face / length
              << " Pa vs rho c v / 2 = " << expected << " Pa; nodes "
              << *std::min_element(mean.begin(), mean.end()) << " to "
              << *std::max_element(mean.begin(), mean.end()) << " Pa over " << count << " frames\n";
  }
} // namespace
