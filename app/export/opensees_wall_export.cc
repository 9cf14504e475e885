// Yielding moat walls as OpenSees nodes, materials and zeroLength elements (Tcl and OpenSeesPy).
#include "app/export/opensees_wall_export.h"

#include <fmt/format.h>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "app/lumped/lumped_scene.h"
#include "io/summary.h"

namespace kimp::app
{
  std::string opensees_number(const double value)
  {
    return fmt::format("{:.10g}", value);
  }

  namespace
  {
    /// One command in either language: `name` with its arguments (numbers, words or variables).
    struct Command
    {
      std::string              name;
      std::vector<std::string> arguments;
    };

    /// A word argument ("damage", "-mat"): quoted in Python, bare in Tcl.
    std::string word(const std::string &w)
    {
      return "'" + w + "'";
    }

    std::string render(const Command &c, const bool python)
    {
      std::string out = python ? "ops." + c.name + "(" : c.name;
      for (std::size_t i = 0; i < c.arguments.size(); ++i)
      {
        std::string a = c.arguments[i];
        if (!python && a.front() == '\'')
          a = a.substr(1, a.size() - 2);
        if (!python && a.rfind("kimp", 0) == 0)
          a = "$" + a; // a variable
        out += python ? (i == 0 ? "" : ", ") + a : " " + a;
      }
      return out + (python ? ")\n" : "\n");
    }

    std::string comment(const std::string &text)
    {
      return "# " + text + "\n";
    }
  } // namespace

  std::vector<OpenSeesGapSpring> opensees_curve_springs(const lumped::WallBackfillParams &part)
  {
    if (part.envelope != lumped::WallEnvelope::curve)
      throw std::invalid_argument("opensees_curve_springs: the envelope is not a curve");
    const std::vector<double>     &w = part.curve_displacements;
    const std::vector<double>     &f = part.curve_forces;
    std::vector<OpenSeesGapSpring> out;
    for (std::size_t i = 0; i + 1 < w.size(); ++i)
    {
      const double slope = (f[i + 1] - f[i]) / (w[i + 1] - w[i]);
      const double next =
        i + 2 < w.size() ? (f[i + 2] - f[i + 1]) / (w[i + 2] - w[i + 1]) : 0.0; // flat past w_n
      const double e = slope - next;
      if (e > 0.0)
        out.push_back({e, e * w[i + 1]});
    }
    return out;
  }

  std::vector<OpenSeesWall> opensees_walls(const LumpedScene &scene)
  {
    const lumped::PoundingScene pounding = make_pounding_scene(scene);
    std::vector<OpenSeesWall>   out;
    for (const auto &[wall, name, right] :
         {std::tuple<const std::optional<lumped::MoatWall> *, const char *, bool>{
            &pounding.left_wall,
            "left_wall",
            false},
          {&pounding.right_wall, "right_wall", true}})
      if (*wall && (*wall)->yielding)
        out.push_back(
          {name, right, (*wall)->oscillator_mass(), (*wall)->clear_gap(), *(*wall)->yielding});
    return out;
  }

  namespace
  {
    /// The ElasticPPGap or HyperbolicGapMaterial of a bilinear or hyperbolic envelope, with its
    /// comment, at `tag`.
    std::string
    single_gap_material(const lumped::WallBackfillParams &p, const int tag, const bool python)
    {
      const bool  bilinear = p.envelope == lumped::WallEnvelope::bilinear;
      std::string out      = comment(
        bilinear ? "wall and backfill: ElasticPPGap E = stiffness, Fy = -capacity, gap 0, "
                        "eta = hardening_ratio, damage (the set is kept); kimp unloads at "
                        "unloading_stiffness, OpenSees at E" :
                   "wall and backfill: HyperbolicGapMaterial Kmax = stiffness, Kur = "
                        "unloading_stiffness, Rf = failure_ratio, Fult = -capacity, gap 0 (OpenSees "
                        "warns that a gap of 0 is not negative and keeps it)");
      std::vector<std::string> backfill = {word(bilinear ? "ElasticPPGap" :
                                                           "HyperbolicGapMaterial"),
                                           std::to_string(tag),
                                           opensees_number(p.stiffness)};
      if (bilinear)
        backfill.insert(backfill.end(),
                        {opensees_number(-p.capacity),
                         "0.0",
                         opensees_number(p.hardening_ratio),
                         word("damage")});
      else
        backfill.insert(backfill.end(),
                        {opensees_number(p.unloading_stiffness),
                         opensees_number(p.failure_ratio),
                         opensees_number(-p.capacity),
                         "0.0"});
      return out + render({"uniaxialMaterial", backfill}, python);
    }

    /// The ElasticPPGap springs of a curve envelope (opensees_curve_springs()) from `tag` on,
    /// with the comments that say how they add up and how their unloading differs from kimp's.
    std::string
    curve_gap_materials(const OpenSeesWall &w, int &tag, std::vector<int> &tags, const bool python)
    {
      const lumped::WallBackfillParams &p = w.part;
      // Never empty: the E_i add up to the first slope, which is positive.
      const std::vector<OpenSeesGapSpring> springs = opensees_curve_springs(p);
      const double                         k       = p.curve_forces[1] / p.curve_displacements[1];
      const double w_c = springs.back().yield_force / springs.back().stiffness;
      std::string  out = comment(fmt::format(
        "wall and backfill: the curve envelope ({} points) as {} ElasticPPGap springs in "
         "parallel (gap 0, eta 0, damage): spring i has E = s_i - s_(i+1), the fall of the "
         "envelope's slope at its point i+1 (s = 0 past the last point), and Fy = -E*w_(i+1); "
         "their sum is the envelope exactly, k = {} N/m at 0, flat at {} N from w = {} m",
        p.curve_displacements.size(),
        springs.size(),
        opensees_number(k),
        opensees_number(p.curve_forces.back()),
        opensees_number(w_c)));
      out += comment(fmt::format(
        "unloading differs: kimp unloads from w_max at max(unloading_stiffness = {} N/m, "
        "E(w_max)/w_max) to the set w_max - E(w_max)/that; the springs unload at k, softer as "
        "each goes slack at its own set w_max - w_(i+1), and keep a set only past the last kink: "
        "max(0, w_max - {} m)",
        opensees_number(p.unloading_stiffness),
        opensees_number(w_c)));
      for (const OpenSeesGapSpring &s : springs)
      {
        tags.push_back(tag);
        out += render({"uniaxialMaterial",
                       {word("ElasticPPGap"),
                        std::to_string(tag++),
                        opensees_number(s.stiffness),
                        opensees_number(-s.yield_force),
                        "0.0",
                        opensees_number(0.0),
                        word("damage")}},
                      python);
      }
      return out;
    }

    /// The wall-and-backfill part of `w` from `tag` on: its gap materials, what has no
    /// counterpart, the dashpot and the Parallel of them all; `part` is the Parallel's tag.
    std::string
    wall_backfill_materials(const OpenSeesWall &w, int &tag, int &part, const bool python)
    {
      const lumped::WallBackfillParams &p = w.part;
      std::string                       out;
      std::vector<int>                  tags;
      if (p.envelope == lumped::WallEnvelope::curve)
        out += curve_gap_materials(w, tag, tags, python);
      else
      {
        tags.push_back(tag);
        out += single_gap_material(p, tag++, python);
      }
      if (p.ultimate_capacity < std::numeric_limits<double>::infinity())
        out += comment(fmt::format("ultimate_capacity = {} N (the cap of the hardening) has no "
                                   "counterpart: ElasticPPGap hardens on past it",
                                   opensees_number(p.ultimate_capacity)));
      if (p.tension_capacity > 0.0)
        out += comment(fmt::format("tension_capacity = {} N (the wall's pull-back) has no "
                                   "counterpart: the gap materials carry compression only",
                                   opensees_number(p.tension_capacity)));
      const int dashpot = tag++;
      part              = tag++;
      out += comment("radiation dashpot: Viscous C = radiation_damping, alpha = 1, in parallel");
      out += render(
        {"uniaxialMaterial",
         {word("Viscous"), std::to_string(dashpot), opensees_number(p.radiation_damping), "1.0"}},
        python);
      std::vector<std::string> parallel = {word("Parallel"), std::to_string(part)};
      for (const int t : tags)
        parallel.push_back(std::to_string(t));
      parallel.push_back(std::to_string(dashpot));
      return out + render({"uniaxialMaterial", parallel}, python);
    }
  } // namespace

  std::string opensees_walls_text(const std::vector<OpenSeesWall> &walls,
                                  const bool                       python,
                                  const int                        first_tag,
                                  const int                        first_node,
                                  const int                        first_element)
  {
    std::string out;
    out += comment(
      fmt::format("kimp export-opensees: yielding moat walls ({})", python ? "OpenSeesPy" : "Tcl"));
    out += comment("Units: N, m, s, kg. A 1D model (model BasicBuilder -ndm 1 -ndf 1) is assumed;");
    out +=
      comment("set kimpBuildingNode to the isolation level's node and kimpImpactMaterial to the");
    out +=
      comment("contact part, one of the materials of opensees_impact (its gap = the wall's gap).");
    out += comment("Compression is negative: capacity and gaps are written negative.");
    out += python ? "import openseespy.opensees as ops\n\nkimpBuildingNode = 1\n"
                    "kimpImpactMaterial = 1\n" :
                    "\nset kimpBuildingNode 1\nset kimpImpactMaterial 1\n";
    int tag = first_tag, node = first_node, element = first_element;
    for (const OpenSeesWall &w : walls)
    {
      const lumped::WallBackfillParams &p         = w.part;
      const int                         wall_node = node++, ground_node = node++;
      out += "\n" + comment(fmt::format("{}: wall node {} with the wall's mass {} kg, fixed ground "
                                        "node {}; the contact part acts across a gap of {} m",
                                        w.name,
                                        wall_node,
                                        opensees_number(w.mass),
                                        ground_node,
                                        opensees_number(w.gap)));
      out +=
        render({"node", {std::to_string(wall_node), "0.0", word("-mass"), opensees_number(w.mass)}},
               python);
      out += render({"node", {std::to_string(ground_node), "0.0"}}, python);
      out += render({"fix", {std::to_string(ground_node), "1"}}, python);
      int part = 0;
      out += wall_backfill_materials(w, tag, part, python);
      // Deformation u_j − u_i is negative when closing: into the backfill for the wall part,
      // towards the wall for the contact part.
      const std::string building = "kimpBuildingNode";
      const std::string wn = std::to_string(wall_node), gn = std::to_string(ground_node);
      out += comment(fmt::format("wall part (wall - ground), then the contact part in series "
                                 "(building - wall); failure_displacement = {} m is kimp's check",
                                 opensees_number(p.failure_displacement)));
      // A zeroLength element in x of `material` from node `i` to node `j` (swapped on the right).
      const auto zero_length = [&](const std::string &i, const std::string &j, std::string material)
      {
        return render({"element",
                       {word("zeroLength"),
                        std::to_string(element++),
                        w.right ? i : j,
                        w.right ? j : i,
                        word("-mat"),
                        std::move(material),
                        word("-dir"),
                        "1"}},
                      python);
      };
      out += zero_length(wn, gn, std::to_string(part));
      out += zero_length(building, wn, "kimpImpactMaterial");
    }
    return out;
  }

  void write_opensees_walls(const std::filesystem::path &scene_file,
                            const std::filesystem::path &tcl_file,
                            const std::filesystem::path &python_file)
  {
    const std::vector<OpenSeesWall> walls = opensees_walls(io::load_scene<LumpedScene>(scene_file));
    if (walls.empty())
      throw std::invalid_argument("export-opensees: " + scene_file.string() +
                                  " has no yielding wall (walls.<side>.yielding)");
    io::write_text_atomic(tcl_file, opensees_walls_text(walls, false));
    io::write_text_atomic(python_file, opensees_walls_text(walls, true));
  }
} // namespace kimp::app
