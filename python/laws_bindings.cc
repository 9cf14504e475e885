// Impact laws, two-body collisions, the effective-COR table of `kimp collide` and the impact-law
// fitter for Python; each law is made by lumped::make_force_law, nothing is re-implemented.
#include <memory>
#include <optional>
#include <pybind11/stl.h>
#include <string>

#include "app/lumped/collide_run.h"
#include "fit/fit_config.h"
#include "fit/fitter.h"
#include "io/scene_io.h"
#include "lumped/collision/two_body.h"
#include "lumped/laws/force_law_factory.h"
#include "lumped/laws/law_traits.h"

#include "python/bindings.h"

namespace kimp::python
{
  namespace
  {
    /// A law made from its spec; every evaluation starts from a fresh (virgin) copy.
    class Law
    {
    public:
      explicit Law(lumped::ForceLawSpec spec)
        : spec_(std::move(spec))
        , law_(lumped::make_force_law(spec_))
      {
      }

      const lumped::ForceLawSpec &spec() const { return spec_; }

      /// First trial from the virgin state: F, dF/dδ, dF/dδ̇.
      lumped::ForceResponse first_trial(double delta, double rate)
      {
        law_->revert_to_start();
        return law_->set_trial(delta, rate);
      }

      /// F along a path, committing every sample (history-dependent laws remember).
      std::vector<double> path(const std::vector<double> &delta, const std::vector<double> &rate)
      {
        if (delta.size() != rate.size())
          throw std::invalid_argument("history: delta and delta_dot have different lengths");
        const std::unique_ptr<lumped::ForceLaw> law = law_->clone();
        law->revert_to_start();
        std::vector<double> force(delta.size());
        for (std::size_t i = 0; i < delta.size(); ++i)
        {
          force[i] = law->set_trial(delta[i], rate[i]).force;
          law->commit();
        }
        return force;
      }

      double stability_stiffness(double max_deformation) const
      {
        return law_->stability_stiffness(max_deformation);
      }

    private:
      lumped::ForceLawSpec              spec_;
      std::unique_ptr<lumped::ForceLaw> law_;
    };

    /// Law.force, Law.stiffness or Law.damping: `Member` of the first trial from the virgin state,
    /// elementwise over numpy arrays of δ and δ̇.
    template <double lumped::ForceResponse::*Member>
    auto first_trial_of()
    {
      return py::vectorize([](Law &l, double delta, double rate)
                           { return l.first_trial(delta, rate).*Member; });
    }

    lumped::TwoBodySetup two_body(double m1, double m2, double v1, double v2, double dt, bool o2)
    {
      lumped::TwoBodySetup setup;
      setup.mass_1     = m1;
      setup.mass_2     = m2;
      setup.velocity_1 = v1;
      setup.velocity_2 = v2;
      setup.time_step  = dt;
      setup.velocity_estimate =
        o2 ? lumped::VelocityEstimate::second_order : lumped::VelocityEstimate::backward_difference;
      setup.validate();
      return setup;
    }

    py::dict fit_dict(fit::FitResult &&r, double peak_tolerance)
    {
      py::dict   d;
      const auto parameter = [](const fit::FitParameter &p)
      { return py::make_tuple(p.value, p.lower, p.upper, p.fitted); };
      d["law"]                         = r.law;
      d["stiffness"]                   = parameter(r.stiffness);
      d["cor"]                         = parameter(r.cor);
      d["exponent"]                    = parameter(r.exponent);
      d["normalised_rms"]              = r.normalised_rms;
      d["normalised_displacement_rms"] = r.normalised_displacement_rms;
      d["function_evaluations"]        = r.function_evaluations;
      d["status"]                      = r.status;
      d["verdict"]                     = fit::fit_verdict(r, peak_tolerance);
      d["fem_peak_force"]              = r.fem_peak_force;
      d["fem_contact_duration"]        = r.fem_contact_duration;
      d["fem_impulse"]                 = r.fem_impulse;
      d["contact_start"]               = r.contact_start;
      d["model_peak_force"]            = r.model_peak_force;
      d["model_contact_duration"]      = r.model_contact_duration;
      d["model_impulse"]               = r.model_impulse;
      d["model_effective_cor"]         = r.model_effective_cor;
      d["peak_force_ratio"]            = r.peak_force_ratio();
      d["impulse_ratio"]               = r.impulse_ratio();
      d["contact_duration_ratio"]      = r.contact_duration_ratio();
      d["time"]                        = to_numpy(std::move(r.time));
      d["fem_force"]                   = to_numpy(std::move(r.fem_force));
      d["model_force"]                 = to_numpy(std::move(r.model_force));
      return d;
    }

    /// One law's traits (lumped/laws/law_traits.h) as a dict; "parameters" lists (keyword, unit,
    /// required, default) in the order of the Python class's arguments.
    py::dict traits_dict(const lumped::LawTraits &t)
    {
      py::list parameters;
      for (const lumped::LawParameter &p : t.parameters)
      {
        py::object value = py::none();
        if (p.name == "exponent")
          value = py::float_(t.default_exponent);
        else if (p.unit == "flag")
          value = py::bool_(p.default_value.value_or(0.0) != 0.0);
        else if (p.default_value)
          value = py::float_(*p.default_value);
        parameters.append(
          py::make_tuple(std::string(p.name), std::string(p.unit), p.required, value));
      }
      py::dict d;
      d["name"]                = std::string(t.name);
      d["number"]              = t.number;
      d["class_name"]          = std::string(t.class_name);
      d["summary"]             = std::string(t.summary);
      d["default_exponent"]    = t.default_exponent;
      d["fixed_exponent"]      = t.fixed_exponent();
      d["uses_cor"]            = t.uses_cor();
      d["uses_effective_mass"] = t.uses_effective_mass();
      d["fittable"]            = t.fittable;
      d["moat_wall_only"]      = t.moat_wall_only;
      d["parameters"]          = parameters;
      return d;
    }

    /** force_law_names(), law_traits(), thesis_cor and the Law class: a force law's response
     *  along a path. */
    void register_law_class(py::module_ &m)
    {
      m.def("force_law_names", &lumped::force_law_names);
      m.def(
        "law_traits",
        []
        {
          py::list list;
          for (const lumped::LawTraits &t : lumped::law_traits())
            list.append(traits_dict(t));
          return list;
        },
        "The impact laws' traits (name, number, class name, default exponent, parameters, ...), "
        "in the order of docs/physics.md §1.");
      m.attr("thesis_cor") = lumped::thesis_cor;

      py::class_<Law>(m, "Law")
        .def(py::init(
               [](const std::string           &law,
                  double                       k,
                  const std::optional<double> &exponent,
                  double                       cor,
                  double                       m_eff,
                  bool                         ye,
                  const std::optional<double> &a1,
                  double                       delta_u,
                  double                       k_w)
               {
                 lumped::ForceLawSpec spec;
                 spec.law                         = law;
                 spec.stiffness                   = k;
                 spec.exponent                    = exponent;
                 spec.cor                         = cor;
                 spec.effective_mass              = m_eff;
                 spec.hertzdamp_ye                = ye;
                 spec.impact_a1                   = a1;
                 spec.bumper_ultimate_deformation = delta_u;
                 spec.bumper_wall_stiffness       = k_w;
                 return Law(spec);
               }),
             py::arg("law"),
             py::arg("k"),
             py::arg("exponent") = py::none(),
             py::arg("cor")      = lumped::thesis_cor,
             py::arg("m_eff")    = 0.0,
             py::arg("ye")       = false,
             py::arg("a1")       = py::none(),
             py::arg("delta_u")  = 0.0,
             py::arg("k_w")      = 0.0)
        .def_property_readonly("law", [](const Law &l) { return l.spec().law; })
        .def("force", first_trial_of<&lumped::ForceResponse::force>())
        .def("stiffness", first_trial_of<&lumped::ForceResponse::stiffness>())
        .def("damping", first_trial_of<&lumped::ForceResponse::damping>())
        .def("path",
             [](Law &l, const DoubleArray &delta, const DoubleArray &rate)
             { return to_numpy(l.path(to_vector(delta), to_vector(rate))); })
        .def("stability_stiffness", &Law::stability_stiffness);
    }

    /** collide(), effective_mass() and cor_table(): two-body collisions of a law. */
    void register_collisions(py::module_ &m)
    {
      m.def(
        "collide",
        [](Law &law, double m1, double m2, double v1, double v2, double dt, bool second_order)
        {
          const lumped::TwoBodySetup setup = two_body(m1, m2, v1, v2, dt, second_order);
          lumped::ForceLawSpec       spec  = law.spec();
          if (spec.effective_mass <= 0.0)
            spec.effective_mass = setup.effective_mass();
          lumped::TwoBodyResult r;
          {
            py::gil_scoped_release release;
            r = lumped::simulate_two_body(*lumped::make_force_law(spec), setup);
          }
          py::dict d;
          d["velocity_1_after"]      = r.velocity_1_after;
          d["velocity_2_after"]      = r.velocity_2_after;
          d["effective_cor"]         = r.effective_cor;
          d["peak_force"]            = r.peak_force;
          d["min_force"]             = r.min_force;
          d["contact_duration"]      = r.contact_duration;
          d["max_penetration"]       = r.max_penetration;
          d["impact_velocity"]       = r.impact_velocity;
          d["kinetic_energy_before"] = r.kinetic_energy_before;
          d["kinetic_energy_loss"]   = r.kinetic_energy_loss;
          d["dissipated_energy"]     = r.dissipated_energy;
          d["permanent_indentation"] = r.permanent_indentation;
          d["momentum_error"]        = r.momentum_error;
          d["n_steps"]               = r.n_steps;
          d["effective_mass"]        = spec.effective_mass;
          d["time"]                  = to_numpy(std::move(r.history.time));
          d["deformation"]           = to_numpy(std::move(r.history.deformation));
          d["rate"]                  = to_numpy(std::move(r.history.rate));
          d["force"]                 = to_numpy(std::move(r.history.force));
          return d;
        },
        py::arg("law"),
        py::arg("mass_1"),
        py::arg("mass_2"),
        py::arg("velocity_1"),
        py::arg("velocity_2"),
        py::arg("time_step"),
        py::arg("second_order"));

      m.def(
        "effective_mass",
        [](double m1, double m2)
        { return two_body(m1, m2, 1.0, 0.0, 1.0, false).effective_mass(); },
        py::arg("mass_1"),
        py::arg("mass_2"),
        "m1·m2/(m1 + m2), kg (m1 against a rigid wall, m2 = inf), as the collision computes it.");
      m.def(
        "cor_table",
        [](const std::string &text, const std::string &name)
        {
          std::vector<app::CollideRow> rows;
          {
            py::gil_scoped_release release;
            rows = app::collide_cor_table(io::load_scene_text<app::CollideScene>(text, name));
          }
          py::list list;
          for (const app::CollideRow &r : rows)
          {
            py::dict d;
            d["name"] = r.name;
            d["law"]  = r.row.law;
            for (const app::CorTableColumn &c : app::cor_table_columns())
              d[c.name] = r.row.*c.value;
            d["status"] = r.status;
            list.append(d);
          }
          return list;
        },
        py::arg("text"),
        py::arg("name"));
    }

    /** fit(): a law fitted to a force history. */
    void register_fit(py::module_ &m)
    {
      m.def(
        "fit",
        [](const DoubleArray                &time,
           const DoubleArray                &force,
           double                            velocity,
           double                            mass,
           const std::string                &law,
           double                            cor,
           const std::optional<double>      &exponent,
           bool                              fit_cor,
           bool                              fit_exponent,
           const std::optional<DoubleArray> &indentation,
           const std::optional<DoubleArray> &slab_displacement,
           double                            displacement_weight,
           double                            wall_mass,
           double                            peak_tolerance)
        {
          if (!(peak_tolerance > 0.0))
            throw std::invalid_argument("peak_tolerance = " + std::to_string(peak_tolerance) +
                                        " (must be > 0)");
          fit::ForceHistory history;
          history.time  = to_vector(time);
          history.force = to_vector(force);
          if (indentation)
            history.indentation = to_vector(*indentation);
          if (slab_displacement)
            history.slab_displacement = to_vector(*slab_displacement);
          lumped::ForceLawSpec spec;
          spec.law      = law;
          spec.cor      = cor;
          spec.exponent = exponent;
          // The window and misfit settings of `kimp fit` and `kimp study` (fit::FitConfig).
          fit::FitOptions options     = fit::fit_options(fit::FitConfig{});
          options.fit_cor             = fit_cor;
          options.fit_exponent        = fit_exponent;
          options.displacement_weight = displacement_weight;
          options.wall_mass           = wall_mass;
          fit::FitResult result;
          {
            py::gil_scoped_release release;
            result = fit::fit_impact_law(history, mass, velocity, spec, options);
          }
          return fit_dict(std::move(result), peak_tolerance);
        },
        py::arg("time"),
        py::arg("force"),
        py::arg("velocity"),
        py::arg("mass"),
        py::arg("law"),
        py::arg("cor"),
        py::arg("exponent"),
        py::arg("fit_cor"),
        py::arg("fit_exponent"),
        py::arg("indentation"),
        py::arg("slab_displacement"),
        py::arg("displacement_weight"),
        py::arg("wall_mass"),
        py::arg("peak_tolerance"));
    }
  } // namespace

  void register_laws(py::module_ &m)
  {
    register_law_class(m);
    register_collisions(m);
    register_fit(m);
  }
} // namespace kimp::python
