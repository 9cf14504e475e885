// Case enumeration of a sweep: key paths are set on a copy of the base scene's YAML tree
// (sweep_values.h), so every scene key can be varied without the sweep knowing the schema; the
// checks of the variants against the base scene and the plan as JSON. The sweep file is read in
// sweep_file.cc.
#include "app/sweep/sweep_plan.h"

#include <algorithm>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "app/sweep/sweep_values.h"
#include "base/hash.h"

namespace kimp::app
{
  using namespace kimp::base;
  namespace sv = sweep_values;
  using sv::fail_at;
  namespace
  {
    /// The base scene `base` with `settings` (key path, YAML value) set, as YAML text.
    std::string with_settings(const YAML::Node                                       &base,
                              const std::vector<std::pair<std::string, std::string>> &settings,
                              const std::string                                      &file_name)
    {
      YAML::Node scene = YAML::Clone(base);
      for (const auto &[path, value] : settings)
        sv::set_node_value(scene, path, sv::resolved_value(path, value, file_name));
      return sv::emit(scene);
    }
  } // namespace

  void SweepPlan::enumerate_cases(const CaseCountCheck &check_count)
  {
    std::size_t n_combinations = 1;
    if (combination_ == SweepCombination::zip)
    {
      n_combinations = parameters_.front().values.size();
      for (const SweepParameter &p : parameters_)
        if (p.values.size() != n_combinations)
          fail_at(file_name_,
                  p.line,
                  "parameters." + p.name,
                  fmt::format("{} values, but {} has {} (combine: zip needs equal lengths)",
                              p.values.size(),
                              parameters_.front().name,
                              n_combinations));
    }
    else
    {
      constexpr std::size_t max_cases = 10'000'000;
      for (const SweepParameter &p : parameters_)
      {
        n_combinations *= p.values.size();
        if (n_combinations > max_cases)
          fail_at(file_name_,
                  p.line,
                  "parameters",
                  fmt::format("more than {} combinations", max_cases));
      }
    }

    if (check_count)
      check_count(n_combinations * (1 + companions_.size()), base_scene_text_, base_scene_name_);
    const YAML::Node base  = sv::load(base_scene_text_, base_scene_name_);
    std::size_t      index = 0;
    for (std::size_t c = 0; c < n_combinations; ++c)
    {
      std::vector<std::string> values(parameters_.size());
      std::vector<std::size_t> choice(parameters_.size());
      std::size_t              rest = c;
      for (std::size_t i = parameters_.size(); i-- > 0;)
      {
        const SweepParameter &p = parameters_[i];
        if (combination_ == SweepCombination::zip)
          choice[i] = c;
        else
        {
          choice[i] = rest % p.values.size();
          rest /= p.values.size();
        }
        values[i] = p.values[choice[i]];
      }
      YAML::Node  scene = YAML::Clone(base);
      std::string signature;
      for (std::size_t i = 0; i < parameters_.size(); ++i)
      {
        const SweepParameter &p = parameters_[i];
        sv::set_values_at(scene, p.settings[choice[i]], file_name_, p.line, "parameters." + p.name);
        signature += p.name + "=" + values[i] + "\n";
        for (const auto &[path, value] : p.settings[choice[i]])
          if (path != p.name || value != values[i])
            signature += "  " + path + "=" + value + "\n";
      }

      const auto add_case = [&](const YAML::Node &case_scene, const std::string &companion)
      {
        SweepCase sc;
        sc.index     = index++;
        sc.companion = companion;
        sc.values    = values;
        const std::uint64_t hash =
          stable_hash(signature + (companion.empty() ? "" : "companion=" + companion + "\n"));
        sc.id         = fmt::format("{}-{:016x}", sc.index, hash);
        sc.scene_text = sv::emit(case_scene);
        sc.scene_name = fmt::format("{} case {}", file_name_, sc.id);
        cases_.push_back(std::move(sc));
      };
      add_case(scene, "");
      for (const SweepCompanion &companion : companions_)
      {
        YAML::Node variant = YAML::Clone(scene);
        sv::set_values_at(variant,
                          companion.overrides,
                          file_name_,
                          companion.line,
                          "companions." + companion.name);
        add_case(variant, companion.name);
      }
    }
  }

  std::vector<SweepPlan::Variant> SweepPlan::variants() const
  {
    std::vector<Variant> out;
    for (const SweepParameter &p : parameters_)
      for (std::size_t v = 0; v < p.values.size(); ++v)
        out.push_back({p.name + " = " + p.values[v],
                       "parameters." + p.name + " = " + p.values[v],
                       p.line,
                       p.settings[v]});
    for (const SweepCompanion &c : companions_)
      out.push_back({"companion " + c.name, "companions." + c.name, c.line, c.overrides});
    return out;
  }

  void SweepPlan::check_variant(const Variant &variant, const SceneChecker &check) const
  {
    const YAML::Node base = sv::load(base_scene_text_, base_scene_name_);
    try
    {
      check(with_settings(base, variant.settings, file_name_),
            base_scene_name_ + " (" + variant.label + ")");
    }
    catch (const std::exception &error)
    {
      fail_at(file_name_, variant.line, variant.key, error.what());
    }
  }

  void SweepPlan::check_key_paths(const SceneChecker &check) const
  {
    for (const Variant &variant : variants())
      check_variant(variant, check);
  }

  void SweepPlan::check_records(const SceneChecker &check) const
  {
    bool set_here = false;
    for (const Variant &variant : variants())
      if (std::any_of(variant.settings.begin(),
                      variant.settings.end(),
                      [](const auto &setting) { return sv::is_record_key(setting.first); }))
      {
        set_here = true;
        check_variant(variant, check);
      }
    // The base scene's own records, reported at its lines, when nothing above replaced them.
    if (!set_here)
      check(base_scene_text_, base_scene_name_);
  }

  std::string SweepPlan::to_json_text() const
  {
    nlohmann::ordered_json json;
    json["file"]       = file_name_;
    json["scene"]      = base_scene_name_;
    json["engine"]     = engine_;
    json["combine"]    = combination_ == SweepCombination::product ? "product" : "zip";
    json["parameters"] = nlohmann::ordered_json::array();
    for (const SweepParameter &p : parameters_)
    {
      // Per value the key paths it sets (map values set their own keys, e.g. gap and separation).
      nlohmann::ordered_json settings = nlohmann::ordered_json::array();
      for (const auto &setting : p.settings)
      {
        nlohmann::ordered_json keys = nlohmann::ordered_json::object();
        for (const auto &[path, value] : setting)
          keys[path] = value;
        settings.push_back(keys);
      }
      json["parameters"].push_back({{"name", p.name},
                                    {"key_paths", p.key_paths},
                                    {"values", p.values},
                                    {"settings", settings}});
    }
    json["companions"] = nlohmann::ordered_json::array();
    for (const SweepCompanion &c : companions_)
    {
      nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
      for (const auto &[path, value] : c.overrides)
        overrides[path] = value;
      json["companions"].push_back({{"name", c.name}, {"overrides", overrides}});
    }
    if (report_)
      json["report"] = {{"kind", report_->kind},
                        {"gap", report_->gap_key},
                        {"title", report_->title}};
    json["n_cases"] = cases_.size();
    return json.dump(2);
  }
} // namespace kimp::app
