// Lumped runs and ground motions for Python: the scene's cases run by app::run_lumped_cases (as
// `kimp lumped` runs them, without files) with the GIL released; histories handed to numpy
// unmoved.
#include <memory>
#include <mutex>
#include <optional>
#include <pybind11/stl.h>
#include <string>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_run.h"
#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_run.h"
#include "io/scene_io.h"

#include "python/bindings.h"

namespace kimp::python
{
  namespace
  {
    /// History of `n` samples of `width` columns as an (n, width) array (n-vector if width 0).
    py::array_t<double> history(std::vector<double> &&values, std::size_t n)
    {
      const std::size_t width = n == 0 ? 0 : values.size() / n;
      return to_numpy(std::move(values),
                      {static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(width)});
    }

    py::dict peaks(lumped::Response &r)
    {
      py::dict d;
      d["displacement"]          = to_numpy(std::move(r.peak_displacement));
      d["absolute_acceleration"] = to_numpy(std::move(r.peak_absolute_acceleration));
      d["interstorey_drift"]     = to_numpy(std::move(r.peak_interstorey_drift));
      return d;
    }

    /// A JSON value of app as the Python objects json.loads() makes of it.
    py::object from_json(const nlohmann::json &value)
    {
      return py::module_::import("json").attr("loads")(value.dump());
    }

    const app::PlanLumpedScene &full_scene(const ParsedScene &parsed)
    {
      if (parsed.kind != "lumped")
        throw std::invalid_argument(parsed.name + " is a " + parsed.kind + " scene, not lumped");
      return parsed.as<app::PlanLumpedScene>();
    }

    const app::LumpedScene &lumped_scene(const ParsedScene &parsed)
    {
      return full_scene(parsed).base;
    }

    /// A run in plan as plain Python objects: per level arrays of (x, y, θ), the corners of
    /// level 0, the contacts; histories (n samples) shaped (n, levels, 3), (n, corners, 2) and
    /// (n, contacts).
    py::dict plan_dict(app::PlanRun &&run)
    {
      lumped::plan::PlanResponse &r  = run.response;
      const auto                  nl = static_cast<py::ssize_t>(r.n_levels);
      const auto                  nc = static_cast<py::ssize_t>(run.contact_names.size());
      py::dict                    d;
      d["name"]             = "default";
      d["status"]           = "ok";
      d["ground_motion"]    = run.motion.name;
      d["dt"]               = r.dt;
      d["dt_critical"]      = run.dt_critical;
      d["n_steps"]          = r.n_steps;
      d["n_levels"]         = r.n_levels;
      d["n_impacts"]        = r.n_impacts();
      d["wall_time"]        = run.wall_time;
      d["contact_names"]    = run.contact_names;
      double   corner_force = 0.0, friction_force = 0.0;
      py::list contacts;
      for (const lumped::plan::PlanContactResult &c : r.contacts)
      {
        corner_force   = std::max(corner_force, c.peak_normal_force);
        friction_force = std::max(friction_force, c.peak_friction_force);
        py::dict cd;
        cd["name"]                = c.name;
        cd["segment"]             = c.segment;
        cd["peak_normal_force"]   = c.peak_normal_force;
        cd["peak_friction_force"] = c.peak_friction_force;
        cd["n_impacts"]           = c.impacts.size();
        cd["dissipated_energy"]   = c.dissipated_energy;
        cd["friction_work"]       = c.friction_work;
        contacts.append(cd);
      }
      d["contacts"] = contacts;
      // Damping, yielding walls and energy as summary.json has them (the same JSON, so the same
      // keys and values).
      d["damping"]        = from_json(app::plan_damping_json(run));
      d["yielding_walls"] = from_json(app::yielding_walls_json(r));
      py::dict p;
      p["base_corner_displacement"] = r.peak_corner_displacement.front();
      p["corner_impact_force"]      = corner_force;
      p["friction_force"]           = friction_force;
      p["top_acceleration"]         = r.peak_horizontal_acceleration.back();
      p["isolator_force"]           = r.peak_isolator_force;
      p["displacement"]             = to_numpy(std::move(r.peak_displacement), {nl, 3});
      p["absolute_acceleration"]    = to_numpy(std::move(r.peak_absolute_acceleration), {nl, 3});
      p["corner_displacement"]      = to_numpy(std::move(r.peak_corner_displacement));
      p["horizontal_acceleration"]  = to_numpy(std::move(r.peak_horizontal_acceleration));
      p["drift_x"]                  = to_numpy(std::move(r.peak_drift_x));
      p["drift_y"]                  = to_numpy(std::move(r.peak_drift_y));
      p["corner_drift"]             = to_numpy(std::move(r.peak_corner_drift));
      p["wall_force"]               = to_numpy(std::move(r.peak_wall_force));
      d["peaks"]                    = p;
      lumped::plan::PlanHistory &h  = r.history;
      const auto                 n  = static_cast<py::ssize_t>(h.time.size());
      const auto                 corners = static_cast<py::ssize_t>(
        n > 0 ? h.corner_displacement.size() / (2 * static_cast<std::size_t>(n)) : run.n_corners);
      py::dict hd;
      hd["time"]                  = to_numpy(std::move(h.time));
      hd["displacement"]          = to_numpy(std::move(h.displacement), {n, nl, 3});
      hd["absolute_acceleration"] = to_numpy(std::move(h.absolute_acceleration), {n, nl, 3});
      hd["corner_displacement"]   = to_numpy(std::move(h.corner_displacement), {n, corners, 2});
      hd["contact_force"]         = to_numpy(std::move(h.contact_force), {n, nc});
      hd["friction_force"]        = to_numpy(std::move(h.friction_force), {n, nc});
      hd["energy_error"]          = to_numpy(std::move(h.energy_error));
      d["history"]                = hd;
      d["energy"]                 = from_json(app::plan_energy_json(r.energy));
      return d;
    }

    /// The case as plain Python objects; its vectors are moved into the arrays.
    py::dict case_dict(app::LumpedCaseResult &&c)
    {
      py::dict d;
      d["name"]              = c.name;
      d["status"]            = c.status;
      d["wall_time"]         = c.wall_time;
      d["pga"]               = c.pga;
      d["dt_critical"]       = c.dt_critical;
      d["governing"]         = c.governing;
      d["contact_names"]     = c.contact_names;
      d["storey_upper_dofs"] = c.storey_upper_dofs;
      py::dict modes;
      for (app::BuildingModes &b : c.buildings)
      {
        py::dict bd;
        bd["period"]           = to_numpy(std::move(b.periods));
        bd["rayleigh_a"]       = b.rayleigh_a;
        bd["rayleigh_b"]       = b.rayleigh_b;
        bd["c_iso"]            = b.c_iso;
        modes[py::str(b.name)] = bd;
      }
      d["modes"] = modes;
      if (!c.ok())
        return d;
      lumped::Response &r = c.response;
      d["dt"]             = r.dt;
      d["n_steps"]        = r.n_steps;
      d["duration"]       = r.duration;
      d["peaks"]          = peaks(r);
      const std::size_t n = r.history.time.size();
      py::dict          h;
      h["time"]                  = to_numpy(std::move(r.history.time));
      h["displacement"]          = history(std::move(r.history.displacement), n);
      h["absolute_acceleration"] = history(std::move(r.history.absolute_acceleration), n);
      h["interstorey_drift"]     = history(std::move(r.history.interstorey_drift), n);
      h["contact_force"]         = history(std::move(r.history.contact_force), n);
      h["energy_input"]          = to_numpy(std::move(r.history.energy_input));
      h["energy_error"]          = to_numpy(std::move(r.history.energy_error));
      h["isolator_force"]        = to_numpy(std::move(r.history.isolator_force));
      h["hysteretic_energy"]     = to_numpy(std::move(r.history.hysteretic_energy));
      d["history"]               = h;
      if (!c.isolator.empty())
      {
        py::dict iso;
        iso["kind"]              = c.isolator;
        iso["peak_force"]        = r.peak_isolator_force;
        iso["dissipated_energy"] = r.energy.hysteretic;
        d["isolator"]            = iso;
      }
      py::list contacts;
      for (lumped::ContactResult &contact : r.contacts)
      {
        py::dict cd;
        cd["name"]            = contact.name;
        cd["peak_force"]      = contact.peak_force;
        cd["impact_time"]     = to_numpy(contact.impact_column(&lumped::ImpactEvent::time));
        cd["impact_velocity"] = to_numpy(contact.impact_column(&lumped::ImpactEvent::velocity));
        cd["permanent_indentation"] = contact.permanent_indentation;
        cd["dissipated_energy"]     = contact.dissipated_energy;
        contacts.append(cd);
      }
      d["contacts"] = contacts;
      py::list walls;
      // The walls' and the energy's numbers under the names of lumped.h5 and summary.json.
      for (const app::YieldingWallLimits &w : c.yielding_walls)
      {
        const app::YieldingWallRecord record = app::yielding_wall_record(w, r.contacts[w.contact]);
        py::dict                      wd;
        wd["name"] = w.wall;
        for (const app::YieldingWallQuantity &q : app::yielding_wall_quantities)
          wd[q.name] = record.*q.value;
        wd["failure_time"] = record.failure_time ? py::cast(*record.failure_time) : py::none();
        walls.append(wd);
      }
      d["walls"] = walls;
      py::dict energy;
      for (const app::EnergyTerm &t : app::energy_terms())
        energy[t.name] = r.energy.*t.value;
      d["energy"] = energy;
      if (c.companion)
        d["companion_peaks"] = peaks(*c.companion);
      return d;
    }

    std::optional<std::filesystem::path> directory(const std::optional<std::string> &text)
    {
      if (!text || text->empty())
        return std::nullopt;
      return std::filesystem::path(*text);
    }

    /**
     * app::load_ground_motion of a synthetic section, remembering the last motion: a loop of
     * runs from Python varies the building and keeps the motion, whose generation (filtering a
     * 20 s record) would otherwise cost more than a short run. The same section gives a bitwise
     * identical record, so reusing it changes no number. Records from files are always read.
     */
    std::shared_ptr<const lumped::GroundMotion>
    last_synthetic_motion(const app::GroundMotionScene &scene)
    {
      static std::mutex                                  mutex;
      static std::string                                 last_key;
      static std::shared_ptr<const lumped::GroundMotion> last;
      const std::string                                  key = io::to_json_text(scene, -1);
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (last && key == last_key)
          return last;
      }
      auto motion = std::make_shared<const lumped::GroundMotion>(app::load_ground_motion(scene));
      const std::lock_guard<std::mutex> lock(mutex);
      last_key = key;
      last     = motion;
      return motion;
    }
  } // namespace

  void register_lumped(py::module_ &m)
  {
    m.def(
      "run_lumped",
      [](const ParsedScene                &parsed,
         const std::optional<std::string> &records_dir,
         const std::optional<std::string> &only_case)
      {
        if (full_scene(parsed).plan)
          throw std::invalid_argument(parsed.name +
                                      " has a plan section: run it with run_plan (kimp.lumped)");
        app::LumpedCasesRun run;
        {
          // Everything below is C++ only: other Python threads run meanwhile.
          py::gil_scoped_release release;
          run = app::run_lumped_cases(lumped_scene(parsed),
                                      parsed.name,
                                      parsed.text,
                                      directory(records_dir),
                                      only_case,
                                      last_synthetic_motion);
        }
        std::vector<app::LumpedCaseResult> &results = run.results;
        py::list                            list;
        for (app::LumpedCaseResult &r : results)
          list.append(case_dict(std::move(r)));
        return list;
      },
      py::arg("scene"),
      py::arg("records_dir") = py::none(),
      py::arg("case")        = py::none(),
      "Run the cases of a lumped scene as `kimp lumped` does (app::run_lumped_cases: the same "
      "records, step budget and messages); a list of plain dicts.");

    m.def(
      "has_plan",
      [](const ParsedScene &parsed) { return full_scene(parsed).plan.has_value(); },
      py::arg("scene"),
      "Whether a lumped scene has a `plan` section (pounding in plan).");

    m.def(
      "run_plan",
      [](const ParsedScene &parsed, const std::optional<std::string> &records_dir)
      {
        app::PlanRun run;
        {
          py::gil_scoped_release release;
          run = app::run_plan(full_scene(parsed), parsed.name, parsed.text, directory(records_dir));
        }
        return plan_dict(std::move(run));
      },
      py::arg("scene"),
      py::arg("records_dir") = py::none(),
      "Run a lumped scene with a `plan` section as `kimp lumped` does (app::run_plan); a plain "
      "dict.");

    m.def(
      "ground_motion",
      [](const ParsedScene &parsed, const std::optional<std::string> &dir)
      {
        lumped::GroundMotion motion;
        {
          py::gil_scoped_release release;
          motion = app::load_ground_motion_at(lumped_scene(parsed).ground_motion,
                                              directory(dir),
                                              parsed.name,
                                              parsed.text,
                                              "ground_motion");
        }
        py::dict d;
        d["name"]         = motion.name;
        d["dt"]           = motion.dt;
        d["pga"]          = motion.pga();
        d["acceleration"] = to_numpy(std::move(motion.acceleration));
        return d;
      },
      py::arg("scene"),
      py::arg("records_dir") = py::none(),
      "The ground motion of a lumped scene's ground_motion section (loaded, scaled, trimmed).");
  }
} // namespace kimp::python
