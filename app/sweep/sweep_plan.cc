// The cases of a sweep, counted from the parameters' lengths and each made on demand: key paths
// are set on the base scene's YAML tree (sweep_values.h), so every scene key can be varied
// without the sweep knowing the schema; the checks of the variants against the base scene and
// the plan as JSON. The sweep file is read in
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

  std::vector<std::pair<std::string, std::string>> SweepParameter::settings(std::size_t v) const
  {
    if (v < map_settings.size() && !map_settings[v].empty())
      return map_settings[v];
    std::vector<std::pair<std::string, std::string>> out;
    const std::string                                value = values[v];
    for (const std::string &path : key_paths)
      out.emplace_back(path, value);
    return out;
  }

  bool SweepParameter::sets(const std::string &key_path) const
  {
    // A value without its own map sets the key paths of the parameter.
    bool scalar_values = map_settings.size() < values.size();
    for (const auto &setting : map_settings)
    {
      scalar_values = scalar_values || setting.empty();
      for (const auto &entry : setting)
        if (entry.first == key_path)
          return true;
    }
    return scalar_values &&
           std::find(key_paths.begin(), key_paths.end(), key_path) != key_paths.end();
  }

  void SweepPlan::count_cases(const CaseCountCheck &check_count)
  {
    // Counted from the lengths alone (a range is not expanded): a zip of unequal lengths or too
    // many combinations is refused before any memory is spent on values or cases.
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
    n_combinations_ = n_combinations;
    if (check_count)
      check_count(n_cases(), base_scene_text_, base_scene_name_);
    // The first combination and its companions made once: a key path that cannot be followed in
    // the base scene is an error of the sweep file now, not of every case later.
    for (std::size_t k = 0; k <= companions_.size(); ++k)
      case_at(k);
  }

  std::vector<std::size_t> SweepPlan::choices(std::size_t c) const
  {
    std::vector<std::size_t> choice(parameters_.size());
    std::size_t              rest = c;
    for (std::size_t i = parameters_.size(); i-- > 0;)
    {
      if (combination_ == SweepCombination::zip)
        choice[i] = c;
      else
      {
        choice[i] = rest % parameters_[i].values.size();
        rest /= parameters_[i].values.size();
      }
    }
    return choice;
  }

  SweepCase SweepPlan::case_header(std::size_t index, std::vector<std::size_t> &choice) const
  {
    if (index >= n_cases())
      throw std::out_of_range(
        fmt::format("{}: case {} of a plan of {} cases", file_name_, index, n_cases()));
    const std::size_t per_combination = 1 + companions_.size();
    const std::size_t k               = index % per_combination;
    choice                            = choices(index / per_combination);
    SweepCase sc;
    sc.index     = index;
    sc.companion = k == 0 ? std::string() : companions_[k - 1].name;
    // The signature of the values (and of what a map value sets) gives the id's hash.
    std::string signature;
    sc.values.resize(parameters_.size());
    for (std::size_t i = 0; i < parameters_.size(); ++i)
    {
      const SweepParameter &p = parameters_[i];
      sc.values[i]            = p.values[choice[i]];
      signature += p.name + "=" + sc.values[i] + "\n";
      for (const auto &[path, value] : p.settings(choice[i]))
        if (path != p.name || value != sc.values[i])
          signature += "  " + path + "=" + value + "\n";
    }
    const std::uint64_t hash =
      stable_hash(signature + (sc.companion.empty() ? "" : "companion=" + sc.companion + "\n"));
    sc.id         = fmt::format("{}-{:016x}", sc.index, hash);
    sc.scene_name = fmt::format("{} case {}", file_name_, sc.id);
    return sc;
  }

  SweepCase SweepPlan::case_info(std::size_t index) const
  {
    std::vector<std::size_t> choice;
    return case_header(index, choice);
  }

  SweepCase SweepPlan::case_at(std::size_t index) const
  {
    std::vector<std::size_t> choice;
    SweepCase                sc = case_header(index, choice);
    // Parsed for each case (a few kB): no YAML tree is shared between threads.
    YAML::Node scene = sv::load(base_scene_text_, base_scene_name_);
    for (std::size_t i = 0; i < parameters_.size(); ++i)
    {
      const SweepParameter &p = parameters_[i];
      sv::set_values_at(scene, p.settings(choice[i]), file_name_, p.line, "parameters." + p.name);
    }
    const std::size_t k = index % (1 + companions_.size());
    if (k > 0)
    {
      const SweepCompanion &companion = companions_[k - 1];
      sv::set_values_at(scene,
                        companion.overrides,
                        file_name_,
                        companion.line,
                        "companions." + companion.name);
    }
    sc.scene_text = sv::emit(scene);
    return sc;
  }

  void SweepPlan::for_each_variant(const std::function<void(const Variant &)> &visit) const
  {
    for (const SweepParameter &p : parameters_)
      for (std::size_t v = 0; v < p.values.size(); ++v)
      {
        const std::string value = p.values[v];
        visit(
          {p.name + " = " + value, "parameters." + p.name + " = " + value, p.line, p.settings(v)});
      }
    for (const SweepCompanion &c : companions_)
      visit({"companion " + c.name, "companions." + c.name, c.line, c.overrides});
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
    for_each_variant([&](const Variant &variant) { check_variant(variant, check); });
  }

  void SweepPlan::check_records(const SceneChecker &check) const
  {
    bool set_here = false;
    for_each_variant(
      [&](const Variant &variant)
      {
        if (std::any_of(variant.settings.begin(),
                        variant.settings.end(),
                        [](const auto &setting) { return sv::is_record_key(setting.first); }))
        {
          set_here = true;
          check_variant(variant, check);
        }
      });
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
      for (std::size_t v = 0; v < p.values.size(); ++v)
      {
        nlohmann::ordered_json keys = nlohmann::ordered_json::object();
        for (const auto &[path, value] : p.settings(v))
          keys[path] = value;
        settings.push_back(keys);
      }
      json["parameters"].push_back({{"name", p.name},
                                    {"key_paths", p.key_paths},
                                    {"values", p.values.to_vector()},
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
    json["n_cases"] = n_cases();
    return json.dump(2);
  }
} // namespace kimp::app
