// Static pushover of wall and backfill (see pushover.h): the structured wall-and-backfill mesh
// with its bar columns and interface node pairs, the load path, and the curve's summary.
#include "fem/pushover.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include "fem/static_plasticity.h"

namespace kimp::fem
{
  namespace
  {
    /// Boundary ids of the pushover mesh (0: free).
    constexpr unsigned int soil_base = 1, far_side = 2, band = 4, wall_back = 5, soil_front = 6,
                           wall_base = 7;
    /// Material ids: plain concrete (or the elastic wall), the bar columns, the soil.
    constexpr unsigned int plain_id = 0, bar_id = 1, soil_id = 2;
    /// The Newton matrix's floor: this fraction of each point's virgin stiffness and of each
    /// interface pair's springs (StaticPlasticityParameters::tangent_floor).
    constexpr double tangent_floor = 1e-3;
    /// Halvings of a step for the IMPL-EX error at most (StaticPlasticityParameters::
    /// max_error_cuts): the concrete's extrapolation error is bounded from increment / 8 on.
    constexpr unsigned int max_error_halvings = 3;
    /// Entries of StaticPlasticityParameters::prescribed.
    constexpr std::size_t wall_base_entry = 2;

    void check(bool ok, const std::string &what)
    {
      if (!ok)
        throw std::invalid_argument("pushover: " + what);
    }

    std::string num(double x)
    {
      return std::to_string(x);
    }

    void check_parameters(const PushoverParameters &p)
    {
      check(p.wall_height > 0 && p.wall_thickness > 0,
            "wall_height = " + num(p.wall_height) +
              " m, wall_thickness = " + num(p.wall_thickness) + " m (must be > 0)");
      check(p.band_bottom >= 0 && p.band_top > p.band_bottom && p.band_top <= p.wall_height,
            "band = [" + num(p.band_bottom) + ", " + num(p.band_top) +
              "] m (must be increasing and within the wall height)");
      check(p.wall != PushoverParameters::Wall::reinforced ||
              (p.cover > 0 && p.cover < p.wall_thickness / 2),
            "cover = " + num(p.cover) + " m (must be in (0, wall_thickness / 2))");
      check(p.element_size > 0 && p.max_element_size >= p.element_size && p.grading >= 1,
            "element_size = " + num(p.element_size) + " m, max_element_size = " +
              num(p.max_element_size) + " m, grading = " + num(p.grading) +
              " (need element_size > 0, max_element_size >= element_size, grading >= 1)");
      check(!p.with_backfill ||
              (p.backfill_width > 0 && p.backfill_height > 0 && p.backfill_height <= p.wall_height),
            "backfill " + num(p.backfill_width) + " m x " + num(p.backfill_height) +
              " m (must be > 0, not above the wall)");
      check(p.with_backfill || p.wall != PushoverParameters::Wall::rigid,
            "a rigid wall needs a backfill");
      check(p.friction >= 0 && p.interface_penalty > 0 && p.k0 >= 0 && p.gravity >= 0,
            "friction = " + num(p.friction) + ", interface_penalty = " + num(p.interface_penalty) +
              ", K0 = " + num(p.k0) + ", gravity = " + num(p.gravity) +
              " (need >= 0, > 0, >= 0, >= 0)");
      check(p.max_iterations > 0, "max_iterations must be > 0");
      check(p.min_increment > 0 && p.min_increment <= p.increment,
            "min_increment = " + num(p.min_increment) +
              " m (must be in (0, increment = " + num(p.increment) + " m])");
      check(p.compression_band >= 0,
            "compression_band = " + num(p.compression_band) + " m (must be >= 0)");
      check(p.step_error_tolerance >= 0,
            "step_error_tolerance = " + num(p.step_error_tolerance) + " (must be >= 0)");
      check(p.tolerance > 0 && p.loose_tolerance >= p.tolerance && p.loose_tolerance < 1,
            "tolerance = " + num(p.tolerance) + ", loose_tolerance = " + num(p.loose_tolerance) +
              " (need 0 < tolerance <= loose_tolerance < 1)");
      check(!p.path.empty() && p.path.front() > 0,
            "path must start with a push (first entry > 0 m)");
      for (const double u : p.path)
        check(std::isfinite(u) && u >= 0, "path entry " + num(u) + " m (must be >= 0)");
      check(p.increment > 0 && p.first_increment > 0 && p.first_increment < p.increment &&
              p.first_increment < p.path.front(),
            "increment = " + num(p.increment) + " m, first_increment = " + num(p.first_increment) +
              " m (need 0 < first_increment < increment and < the "
              "first path entry)");
    }

    /** Halvings of `increment` down to the smallest not below `min_increment`. */
    unsigned int step_halvings(const PushoverParameters &p)
    {
      unsigned int cuts = 0;
      while (cuts < 30 && p.increment * std::pow(0.5, cuts + 1) >= p.min_increment * (1 - 1e-12))
        ++cuts;
      return cuts;
    }

    /** Grid lines over [a, b] through every break point in it, cells of at most @p h. */
    std::vector<double> lines_through(std::vector<double> breaks, double h)
    {
      std::sort(breaks.begin(), breaks.end());
      breaks.erase(std::unique(breaks.begin(),
                               breaks.end(),
                               [&](double x, double y) { return std::abs(x - y) < 1e-9 * h; }),
                   breaks.end());
      std::vector<double> out{breaks.front()};
      for (std::size_t i = 1; i < breaks.size(); ++i)
      {
        const double len = breaks[i] - breaks[i - 1];
        const auto   n   = static_cast<unsigned int>(std::max(1.0, std::ceil(len / h - 1e-9)));
        for (unsigned int k = 1; k <= n; ++k)
          out.push_back(k == n ? breaks[i] : breaks[i - 1] + len * k / n);
      }
      return out;
    }

    /** Grid lines from a to b: first cell h, growing by @p ratio up to h_max, scaled to fit. */
    std::vector<double> graded_lines(double a, double b, double h, double ratio, double h_max)
    {
      std::vector<double> sizes;
      double              total = 0, size = h;
      while (total < (b - a) * (1 - 1e-9))
      {
        sizes.push_back(size);
        total += size;
        size = std::min(size * ratio, h_max);
      }
      if (sizes.size() > 1 && total - (b - a) > 0.5 * sizes.back())
      {
        total -= sizes.back();
        sizes.pop_back();
      }
      std::vector<double> out{a};
      for (const double s : sizes)
        out.push_back(out.back() + s * (b - a) / total);
      out.back() = b;
      return out;
    }

    /** The structured mesh, its interface pairs and the material of each cell. */
    struct Model
    {
      PlaneMesh                        mesh;
      std::vector<StaticInterfacePair> pairs;
      double                           bar_column_width = 0; ///< m
    };

    /** Wall x lines: bar columns of width w centred at the cover from each face. */
    std::vector<double> wall_lines(const PushoverParameters &p, double &bar_width)
    {
      const double t = p.wall_thickness, h = p.element_size;
      if (p.wall != PushoverParameters::Wall::reinforced)
        return lines_through({0, t}, h);
      bar_width      = std::min({h, p.cover, t / 2 - p.cover});
      const double c = p.cover, w = bar_width / 2;
      return lines_through({0, c - w, c + w, t - c - w, t - c + w, t}, h);
    }

    Model build_model(const PushoverParameters &p)
    {
      Model                     m;
      const double              t = p.wall_thickness, H = p.wall_height, h = p.element_size;
      const double              Hb       = p.with_backfill ? p.backfill_height : H;
      const std::vector<double> ys       = lines_through({0, p.band_bottom, p.band_top, Hb, H}, h);
      std::vector<double>       xs       = wall_lines(p, m.bar_column_width);
      const std::size_t         n_wall_x = xs.size() - 1, ix_back = n_wall_x;
      if (p.with_backfill)
      {
        const std::vector<double> soil =
          graded_lines(t, t + p.backfill_width, h, p.grading, p.max_element_size);
        xs.insert(xs.end(), soil.begin() + 1, soil.end());
      }
      std::size_t n_ys_soil = 0;
      while (n_ys_soil < ys.size() && ys[n_ys_soil] <= Hb + 1e-9 * h)
        ++n_ys_soil;
      std::map<std::tuple<std::size_t, std::size_t, int>, unsigned int> ids;
      const auto vertex = [&](std::size_t ix, std::size_t iy, bool soil)
      {
        const int  side = soil && p.interface_contact && ix == ix_back ? 1 : 0;
        const auto key  = std::make_tuple(ix, iy, side);
        const auto it   = ids.find(key);
        if (it != ids.end())
          return it->second;
        const auto id = static_cast<unsigned int>(m.mesh.vertices.size());
        m.mesh.vertices.push_back({{xs[ix], ys[iy]}});
        ids.emplace(key, id);
        return id;
      };
      const auto add_edge = [&](unsigned int a, unsigned int b, unsigned int id) {
        m.mesh.boundary_edges.push_back({{{a, b}}, id});
      };
      const double bar_lo = p.cover - m.bar_column_width / 2,
                   bar_hi = t - p.cover + m.bar_column_width / 2;
      for (std::size_t ix = 0; ix + 1 < xs.size(); ++ix)
      {
        const bool        soil = ix >= n_wall_x;
        const std::size_t n_y  = soil ? n_ys_soil - 1 : ys.size() - 1;
        for (std::size_t iy = 0; iy < n_y; ++iy)
        {
          PlaneMesh::Cell cell;
          cell.vertices        = {{vertex(ix, iy, soil),
                                   vertex(ix + 1, iy, soil),
                                   vertex(ix, iy + 1, soil),
                                   vertex(ix + 1, iy + 1, soil)}};
          const double xc      = 0.5 * (xs[ix] + xs[ix + 1]);
          const bool   in_bars = p.wall == PushoverParameters::Wall::reinforced &&
                               ((xc > bar_lo && xc < bar_lo + m.bar_column_width) ||
                                (xc < bar_hi && xc > bar_hi - m.bar_column_width));
          cell.material = soil ? soil_id : in_bars ? bar_id : plain_id;
          m.mesh.cells.push_back(cell);
          const auto &v = cell.vertices;
          if (iy == 0)
            add_edge(v[0], v[1], soil ? soil_base : wall_base);
          if (ix == 0)
          {
            const double yc = 0.5 * (ys[iy] + ys[iy + 1]);
            if (yc > p.band_bottom && yc < p.band_top)
              add_edge(v[0], v[2], band);
          }
          if (soil && ix + 2 == xs.size())
            add_edge(v[1], v[3], far_side);
          if (p.with_backfill && p.interface_contact && ix + 1 == n_wall_x && iy + 1 < n_ys_soil)
            add_edge(v[1], v[3], wall_back);
          if (p.interface_contact && soil && ix == n_wall_x)
            add_edge(v[0], v[2], soil_front);
        }
      }
      if (p.with_backfill && p.interface_contact)
        for (std::size_t iy = 1; iy < n_ys_soil; ++iy) // the base pair is held on both sides
        {
          const double below = iy > 0 ? ys[iy] - ys[iy - 1] : 0;
          const double above = iy + 1 < n_ys_soil ? ys[iy + 1] - ys[iy] : 0;
          const double k = p.interface_penalty * p.soil.youngs_modulus / h * 0.5 * (below + above);
          StaticInterfacePair pair;
          pair.vertex_a             = vertex(ix_back, iy, false);
          pair.vertex_b             = vertex(ix_back, iy, true);
          pair.normal_stiffness     = k;
          pair.tangential_stiffness = k;
          pair.friction             = p.friction;
          m.pairs.push_back(pair);
        }
      return m;
    }

    /** Laws, densities and numerical tangents of the wall and soil. */
    void set_laws(const PushoverParameters &p, double bar_width, StaticPlasticityParameters &s)
    {
      using Wall = PushoverParameters::Wall;
      if (p.wall == Wall::reinforced)
      {
        ReinforcementParameters plain = p.bars, barred = p.bars;
        plain.ratio_y = 0;
        // Half the section's vertical steel in each bar column.
        barred.ratio_y = p.bars.ratio_y * p.wall_thickness / 2 / bar_width;
        // Tension stiffening: every cell's cracks are bridged by the section's smeared bars.
        plain.bridging_ratio_x = barred.bridging_ratio_x = p.bars.ratio_x;
        plain.bridging_ratio_y = barred.bridging_ratio_y = p.bars.ratio_y;
        check(barred.ratio_y < 1,
              "the bars' area exceeds their column of cells (ratio_y = " + num(p.bars.ratio_y) +
                ")");
        const auto         update   = p.implex ? ConcreteDamageLaw::DamageUpdate::implex :
                                                 ConcreteDamageLaw::DamageUpdate::implicit;
        ConcreteParameters concrete = p.concrete;
        concrete.rotating_crack     = p.rotating_crack;
        concrete.compression_band   = p.compression_band;
        s.laws[plain_id]            = std::make_shared<ConcreteDamageLaw>(concrete, plain, update);
        s.laws[bar_id]              = std::make_shared<ConcreteDamageLaw>(concrete, barred, update);
        s.numerical_tangent         = {plain_id, bar_id};
        s.anchoring_boundaries      = {wall_base};
      }
      else
      {
        Material wall = p.wall_elastic;
        if (p.wall == Wall::rigid)
          wall.youngs_modulus *= 1000;
        s.laws[plain_id] = std::make_shared<LinearElasticLaw>(wall);
      }
      s.densities[plain_id] = s.densities[bar_id] = p.wall_density;
      if (p.with_backfill)
      {
        s.laws[soil_id]      = std::make_shared<MohrCoulombLaw>(p.soil);
        s.densities[soil_id] = p.soil.density;
      }
    }

    /** Supports, band and load path (load factor times u_scale is the band displacement). */
    void set_loading(const PushoverParameters &p, double u_scale, StaticPlasticityParameters &s)
    {
      const bool rigid = p.wall == PushoverParameters::Wall::rigid;
      // Entry order: soil base, far side, wall base (wall_base_entry). The band is a uniform
      // load whose mean displacement is controlled: it lets the wall face rotate under it.
      s.prescribed      = {{soil_base, true, true, 0, 0},
                           {far_side, true, false, 0, 0},
                           {wall_base, true, true, rigid ? u_scale : 0.0, 0}};
      s.controlled_load = ControlledLoad{band, u_scale};
      if (!p.with_backfill)
        s.prescribed[0] = s.prescribed[1] = s.prescribed[2]; // no soil: repeat the wall base
      s.n_steps   = static_cast<unsigned int>(std::ceil(u_scale / p.increment - 1e-9));
      s.load_path = {p.first_increment / u_scale};
      for (const double u : p.path)
        s.load_path.push_back(u / u_scale);
    }

    double band_force(const StaticStep &step, bool rigid)
    {
      return step.controlled_force + (rigid ? step.reactions[wall_base_entry][0] : 0.0);
    }
  } // namespace

  PushoverResult run_pushover(const PushoverParameters &p, std::ostream *log)
  {
    check_parameters(p);
    const bool                 rigid = p.wall == PushoverParameters::Wall::rigid;
    Model                      model = build_model(p);
    StaticPlasticityParameters s;
    s.mesh      = std::move(model.mesh);
    s.interface = std::move(model.pairs);
    set_laws(p, model.bar_column_width, s);
    const double u_scale = *std::max_element(p.path.begin(), p.path.end());
    set_loading(p, u_scale, s);
    if (p.geostatic)
    {
      s.gravity = p.gravity;
      if (p.with_backfill)
      {
        const InitialStressField soil =
          geostatic_stress(p.backfill_height, p.soil.density * p.gravity, p.k0);
        const double t   = p.wall_thickness;
        s.initial_stress = [soil, t](double x, double y)
        { return x > t ? soil(x, y) : VoigtStress{}; };
      }
    }
    // Segment k of the solver's path is path entry k - 1 (segment 0: the first increment).
    std::vector<bool> unloading(s.load_path.size(), false);
    for (std::size_t k = 1; k < s.load_path.size(); ++k)
      unloading[k] = s.load_path[k] < s.load_path[k - 1];
    s.end_segment = [&](const std::vector<StaticStep> &steps, std::size_t segment)
    {
      return unloading[segment] &&
             band_force(steps.back(), rigid) - band_force(steps.front(), rigid) <= 0;
    };
    s.max_cuts             = step_halvings(p);
    s.max_error_cuts       = std::min(s.max_cuts, max_error_halvings);
    s.grow_after           = p.grow_after;
    s.newton_tolerance     = p.tolerance;
    s.loose_tolerance      = p.loose_tolerance;
    s.max_iterations       = p.max_iterations;
    s.damped_newton        = true;
    s.step_error_tolerance = p.implex ? p.step_error_tolerance : 0.0;
    // A step starts from the last one's increment carried on (the soil's passive mechanism,
    // the hinge's rotation), and the Newton matrix keeps a floor of the virgin stiffness where
    // the soil sits at the apex of its yield surface and interface pairs open (an unloading
    // wall): docs/physics.md §6 "Static pushover", "Newton".
    s.extrapolated_predictor = true;
    s.tangent_floor          = tangent_floor;
    // The floor falls with the out-of-balance force: the consistent tangent's quadratic rate
    // near the solution (docs/physics.md §6 "Static pushover", "Newton").
    s.floor_follows_residual            = true;
    const StaticPlasticityResult solved = run_static_plasticity(s, log);

    PushoverResult out;
    out.geostatic_force     = band_force(solved.steps.front(), rigid);
    out.plastic_dissipation = solved.plastic_dissipation;
    out.damage_dissipation  = solved.damage_dissipation;
    out.n_cells             = s.mesh.cells.size();
    out.n_dofs              = solved.n_dofs;
    out.n_interface_pairs   = static_cast<unsigned int>(s.interface.size());
    out.step_control        = solved.step_control;
    for (std::size_t c = 0; c < solved.cell_states.size(); ++c)
    {
      PushoverCell pc;
      pc.state   = solved.cell_states[c];
      pc.in_wall = pc.state.centre[0] < p.wall_thickness;
      pc.in_bars = s.mesh.cells[c].material == bar_id;
      out.cells.push_back(pc);
    }
    out.curve.push_back({0, 0, 0, false});
    for (std::size_t k = 1; k < solved.steps.size(); ++k)
    {
      const StaticStep &step = solved.steps[k];
      PushoverPoint     point;
      point.displacement = step.load_factor * u_scale;
      point.force        = band_force(step, rigid) - out.geostatic_force;
      point.segment      = static_cast<unsigned int>(step.segment == 0 ? 0 : step.segment - 1);
      point.unloading    = unloading[step.segment];
      if (step.segment > 0)
      {
        const double du = std::abs(point.displacement - out.curve.back().displacement);
        out.smallest_increment =
          out.smallest_increment > 0 ? std::min(out.smallest_increment, du) : du;
      }
      out.curve.push_back(point);
      out.step_residuals.push_back(step.residuals);
    }
    return out;
  }

  double envelope_force(const std::vector<PushoverPoint> &curve, double u)
  {
    double               u_max    = -std::numeric_limits<double>::infinity();
    const PushoverPoint *previous = nullptr;
    for (const PushoverPoint &point : curve)
    {
      if (point.unloading || point.displacement < u_max)
        continue;
      if (previous != nullptr && u >= previous->displacement && u <= point.displacement &&
          point.displacement > previous->displacement)
        return previous->force + (point.force - previous->force) * (u - previous->displacement) /
                                   (point.displacement - previous->displacement);
      u_max    = point.displacement;
      previous = &point;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

  PushoverSummary summarise_pushover(const std::vector<PushoverPoint> &curve)
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    PushoverSummary  s;
    s.unloading_stiffness = s.permanent_set = s.unloaded_from = nan;
    if (curve.size() < 2)
      return s;
    s.initial_stiffness = curve[1].force / curve[1].displacement;
    for (const PushoverPoint &point : curve)
      if (point.force > s.capacity)
      {
        s.capacity                 = point.force;
        s.displacement_at_capacity = point.displacement;
      }
    for (std::size_t k = 1; k < curve.size(); ++k)
      if (!curve[k].unloading && curve[k].force >= 0.75 * s.capacity)
      {
        const PushoverPoint &a = curve[k - 1], &b = curve[k];
        const double         u = a.displacement + (b.displacement - a.displacement) *
                                            (0.75 * s.capacity - a.force) / (b.force - a.force);
        s.cracked_stiffness = 0.75 * s.capacity / u;
        break;
      }
    s.force_at_1cm = envelope_force(curve, 0.01);
    // The first unloading: from the point before it to zero force (or its last point).
    for (std::size_t k = 1; k < curve.size(); ++k)
      if (curve[k].unloading)
      {
        const PushoverPoint &top = curve[k - 1];
        s.unloaded_from          = top.displacement;
        std::size_t j            = k;
        while (j + 1 < curve.size() && curve[j + 1].unloading && curve[j].force > 0)
          ++j;
        const PushoverPoint &a = curve[j - 1], &b = curve[j];
        if (b.force <= 0 && a.force > 0)
          s.permanent_set =
            a.displacement + (b.displacement - a.displacement) * a.force / (a.force - b.force);
        const double end_u = std::isnan(s.permanent_set) ? b.displacement : s.permanent_set;
        const double end_f = std::isnan(s.permanent_set) ? b.force : 0.0;
        if (top.displacement > end_u)
          s.unloading_stiffness = (top.force - end_f) / (top.displacement - end_u);
        break;
      }
    return s;
  }
} // namespace kimp::fem
