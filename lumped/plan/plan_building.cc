// Building in plan: validation, mass and stiffness matrices, per-direction damping, modes.
#include "lumped/plan/plan_building.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace kimp::lumped::plan
{
  namespace
  {
    void fail(const std::string &where, const std::string &what)
    {
      throw std::invalid_argument(where + " " + what);
    }

    std::string num(const double v)
    {
      std::ostringstream s;
      s << v;
      return s.str();
    }

    /// Add the spring of stiffness diag(k_x, k_y) joining the material points at `point` of
    /// `lower` (−1: the ground) and `upper` to k.
    void add_point_spring(const PlanBuilding &b,
                          Eigen::MatrixXd    &k,
                          const int           lower,
                          const int           upper,
                          const Point        &point,
                          const double        k_x,
                          const double        k_y)
    {
      Eigen::Matrix<double, 2, 6> g = Eigen::Matrix<double, 2, 6>::Zero();
      g.rightCols<3>()              = level_kinematics(b, static_cast<std::size_t>(upper), point);
      if (lower >= 0)
        g.leftCols<3>() = -level_kinematics(b, static_cast<std::size_t>(lower), point);
      const Eigen::Matrix<double, 6, 6> ke =
        g.transpose() * Eigen::Vector2d(k_x, k_y).asDiagonal() * g;
      const int first[2] = {3 * lower, 3 * upper};
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c)
          if (first[a] >= 0 && first[c] >= 0)
            k.block<3, 3>(first[a], first[c]) += ke.block<3, 3>(3 * a, 3 * c);
    }

    void add_torsion(Eigen::MatrixXd &k, const int lower, const int upper, const double k_theta)
    {
      const int u = 3 * upper + 2;
      k(u, u) += k_theta;
      if (lower >= 0)
      {
        const int l = 3 * lower + 2;
        k(l, l) += k_theta;
        k(l, u) -= k_theta;
        k(u, l) -= k_theta;
      }
    }
  } // namespace

  double PlanLevel::inertia() const
  {
    if (polar_inertia)
      return *polar_inertia;
    const Point c = centroid(outline);
    return mass * polar_moment(outline, c) / std::abs(signed_area(outline));
  }

  PlanStorey
  storey(const double k_x, const double k_y, const double k_theta, const Point &stiffness_centre)
  {
    return PlanStorey{{StoreyElement{stiffness_centre, k_x, k_y}}, k_theta};
  }

  void validate(const PlanBuilding &b)
  {
    const std::size_t n = b.n_levels();
    if (n == 0)
      fail(b.name + ".levels", "is empty (need >= 1 level)");
    for (std::size_t i = 0; i < n; ++i)
    {
      const PlanLevel  &l = b.levels[i];
      const std::string w = b.name + ".levels[" + std::to_string(i) + "]";
      if (!(std::isfinite(l.mass) && l.mass > 0.0))
        fail(w + ".mass", "= " + num(l.mass) + " kg (must be > 0)");
      validate_polygon(l.outline, w + ".outline");
      if (!l.mass_eccentricity.allFinite())
        fail(w + ".mass_eccentricity", "is not finite");
      if (l.polar_inertia && !(std::isfinite(*l.polar_inertia) && *l.polar_inertia > 0.0))
        fail(w + ".polar_inertia", "= " + num(*l.polar_inertia) + " kg*m^2 (must be > 0)");
    }
    const std::size_t n_storeys = b.is_isolated() ? n - 1 : n;
    if (b.storeys.size() != n_storeys)
      fail(b.name + ".storeys",
           "has " + std::to_string(b.storeys.size()) + " entries (expected " +
             std::to_string(n_storeys) + " for " + std::to_string(n) + " levels, " +
             (b.is_isolated() ? "isolated" : "fixed base") + ")");
    for (std::size_t s = 0; s < b.storeys.size(); ++s)
    {
      const std::string w  = b.name + ".storeys[" + std::to_string(s) + "]";
      const PlanStorey &st = b.storeys[s];
      if (!(std::isfinite(st.k_theta) && st.k_theta >= 0.0))
        fail(w + ".k_theta", "= " + num(st.k_theta) + " N*m/rad (must be >= 0)");
      for (std::size_t e = 0; e < st.elements.size(); ++e)
      {
        const StoreyElement &el = st.elements[e];
        const std::string    we = w + ".elements[" + std::to_string(e) + "]";
        if (!el.position.allFinite())
          fail(we + ".position", "is not finite");
        if (!(std::isfinite(el.k_x) && el.k_x >= 0.0))
          fail(we + ".k_x", "= " + num(el.k_x) + " N/m (must be >= 0)");
        if (!(std::isfinite(el.k_y) && el.k_y >= 0.0))
          fail(we + ".k_y", "= " + num(el.k_y) + " N/m (must be >= 0)");
      }
    }
    for (std::size_t j = 0; j < b.isolators.size(); ++j)
    {
      const std::string w = b.name + ".isolators[" + std::to_string(j) + "]";
      if (!b.isolators[j].law)
        fail(w, "has no isolator law");
      if (!b.isolators[j].position.allFinite())
        fail(w + ".position", "is not finite");
    }
    if (!(b.damping_ratio >= 0.0 && b.damping_ratio < 1.0))
      fail(b.name + ".damping_ratio", "= " + num(b.damping_ratio) + " (must be in [0, 1))");
    if (b.is_isolated() &&
        !(b.isolation_damping_ratio >= b.damping_ratio && b.isolation_damping_ratio < 1.0))
      fail(b.name + ".isolation_damping_ratio",
           "= " + num(b.isolation_damping_ratio) +
             " (must be in [damping_ratio = " + num(b.damping_ratio) + ", 1))");
  }

  Eigen::Matrix<double, 2, 3>
  level_kinematics(const PlanBuilding &b, const std::size_t level, const Point &point)
  {
    return point_kinematics(point, b.levels[level].centre_of_mass());
  }

  Eigen::VectorXd plan_masses(const PlanBuilding &b)
  {
    Eigen::VectorXd m(static_cast<Eigen::Index>(b.n_dofs()));
    for (std::size_t i = 0; i < b.n_levels(); ++i)
    {
      const auto r = static_cast<Eigen::Index>(3 * i);
      m(r)         = b.levels[i].mass;
      m(r + 1)     = b.levels[i].mass;
      m(r + 2)     = b.levels[i].inertia();
    }
    return m;
  }

  Eigen::MatrixXd plan_stiffness(const PlanBuilding &b, const bool include_isolators)
  {
    validate(b);
    const auto      n      = static_cast<Eigen::Index>(b.n_dofs());
    Eigen::MatrixXd k      = Eigen::MatrixXd::Zero(n, n);
    const int       offset = b.is_isolated() ? 1 : 0;
    for (std::size_t s = 0; s < b.storeys.size(); ++s)
    {
      const int upper = static_cast<int>(s) + offset;
      const int lower = upper - 1;
      for (const StoreyElement &e : b.storeys[s].elements)
        add_point_spring(b, k, lower, upper, e.position, e.k_x, e.k_y);
      add_torsion(k, lower, upper, b.storeys[s].k_theta);
    }
    if (include_isolators)
      for (const PlanIsolatorSpec &iso : b.isolators)
      {
        const double k1 = iso.law->initial_stiffness();
        add_point_spring(b, k, -1, 0, iso.position, k1, k1);
      }
    return k;
  }

  namespace
  {
    /// Per-direction Rayleigh damping (PlanDamping::matrix), its coefficients into d.rayleigh.
    Eigen::MatrixXd rayleigh_matrix(const PlanBuilding    &b,
                                    const Eigen::VectorXd &m,
                                    const Eigen::MatrixXd &k,
                                    PlanDamping           &d)
    {
      const std::size_t n    = b.n_levels();
      const double      zeta = b.damping_ratio;
      Eigen::VectorXd   sb   = Eigen::VectorXd::Zero(m.size());
      for (int dir = 0; dir < 3; ++dir)
      {
        if (zeta > 0.0)
        {
          // The direction's block: DOFs 3i + dir.
          Eigen::VectorXd md(static_cast<Eigen::Index>(n));
          Eigen::MatrixXd kd(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
          for (std::size_t i = 0; i < n; ++i)
          {
            md(static_cast<Eigen::Index>(i)) = m(static_cast<Eigen::Index>(3 * i) + dir);
            for (std::size_t j = 0; j < n; ++j)
              kd(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                k(static_cast<Eigen::Index>(3 * i) + dir, static_cast<Eigen::Index>(3 * j) + dir);
          }
          ModalProperties modes;
          try
          {
            modes = modal_analysis(md, kd);
          }
          catch (const std::invalid_argument &e)
          {
            // A direction without stiffness (no storey or isolator resists it) has no modes.
            throw std::invalid_argument(b.name + ": the Rayleigh damping along " +
                                        (dir == 0 ? "x" :
                                         dir == 1 ? "y" :
                                                    "theta") +
                                        " needs stiffness in that direction (" + e.what() + ")");
          }
          d.rayleigh[dir] =
            rayleigh_coefficients(modes.omega(0), modes.omega(modes.omega.size() - 1), zeta, zeta);
        }
        for (std::size_t i = 0; i < n; ++i)
        {
          sb(static_cast<Eigen::Index>(3 * i) + dir) = std::sqrt(d.rayleigh[dir].b);
        }
      }
      // a_d·m and b_d·K_ij within a direction exactly as the planar model forms them;
      // √(b_i·b_j)·K_ij between directions.
      Eigen::MatrixXd c = Eigen::MatrixXd::Zero(m.size(), m.size());
      for (Eigen::Index i = 0; i < m.size(); ++i)
      {
        c(i, i) = d.rayleigh[i % 3].a * m(i);
        for (Eigen::Index j = 0; j < m.size(); ++j)
          c(i, j) += (i % 3 == j % 3 ? d.rayleigh[i % 3].b : sb(i) * sb(j)) * k(i, j);
      }
      return c;
    }

    /// c_iso per direction at level 0 and the devices' dashpots (isolated buildings).
    void add_isolation_damping(const PlanBuilding &b, PlanDamping &d)
    {
      const double zeta = b.damping_ratio;
      if (b.is_isolated())
      {
        const Point c0    = b.levels[0].centre_of_mass();
        double      m_tot = 0.0, j_tot = 0.0, k_iso = 0.0, k_iso_theta = 0.0;
        for (const PlanLevel &l : b.levels)
        {
          m_tot += l.mass;
          j_tot += l.inertia() + l.mass * (l.centre_of_mass() - c0).squaredNorm();
        }
        for (const PlanIsolatorSpec &iso : b.isolators)
        {
          const double k1 = iso.law->initial_stiffness();
          k_iso += k1;
          k_iso_theta += k1 * (iso.position - c0).squaredNorm();
          const Eigen::Matrix<double, 2, 3> t = level_kinematics(b, 0, iso.position);
          d.matrix.topLeftCorner<3, 3>() += iso.law->viscous_coefficient() * t.transpose() * t;
        }
        const double extra = b.isolation_damping_ratio - zeta;
        d.c_iso[0]         = 2.0 * extra * std::sqrt(m_tot * k_iso);
        d.c_iso[1]         = d.c_iso[0];
        d.c_iso[2]         = 2.0 * extra * std::sqrt(j_tot * k_iso_theta);
        for (int dir = 0; dir < 3; ++dir)
          d.matrix(dir, dir) += d.c_iso[dir];
      }
    }
  } // namespace

  PlanDamping plan_damping(const PlanBuilding &b)
  {
    validate(b);
    const Eigen::VectorXd m    = plan_masses(b);
    const Eigen::MatrixXd k    = plan_stiffness(b, true);
    const double          zeta = b.damping_ratio;
    PlanDamping           d;
    if (b.damping == PlanDampingModel::modal)
    {
      // Modes of the coupled building (x, y and θ together), ζ in every one.
      d.modes  = modal_analysis(m, k);
      d.matrix = modal_damping_matrix(m, d.modes, Eigen::VectorXd::Constant(m.size(), zeta));
    }
    else
      d.matrix = rayleigh_matrix(b, m, k, d);
    add_isolation_damping(b, d);
    return d;
  }


  ModalProperties plan_modes(const PlanBuilding &b)
  {
    return modal_analysis(plan_masses(b), plan_stiffness(b, true));
  }
} // namespace kimp::lumped::plan
