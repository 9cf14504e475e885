// The schema of every scene kind (--print-schema): every numeric key declares its admissible range
// with its declaration (so the reader enforces it and the defaults and the schema print it), apart
// from the few listed below with the reason they have none; the sweep file's fixed words are
// choices with their options.
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "app/export/opensees_export.h"
#include "app/laws/fit_run.h"
#include "app/lumped/collide_run.h"
#include "app/lumped/lumped_scene.h"
#include "app/sweep/sweep_plan.h"
#include "io/scene_io.h"
#include "tests/support/messages.h"
#ifdef KIMP_WITH_FEM
#  include "app/fem/fem_scene.h"
#  include "app/study/study_scene.h"
#endif

namespace
{
  /// Numeric keys that truly have no bound: key path -> why. A key listed here that gains a range,
  /// or disappears, fails the test too, so the list stays exact.
  const std::map<std::string, std::string> unbounded_keys = {
    // Bouc-Wen gamma may be negative (a softening loop); beta + gamma > 0 and beta >= |gamma| link
    // it to beta and are rules of validate().
    {"isolator.gamma", "Bouc-Wen gamma"},
    // The phase of the synthetic velocity pulse: any real number (radians, periodic).
    {"ground_motion.synthetic.nu", "pulse phase"},
    {"records[].synthetic.nu", "pulse phase (study records)"},
  };

  bool is_numeric(const std::string &type)
  {
    return type == "quantity" || type == "optional quantity" || type == "quantity_list" ||
           type == "integer";
  }

  /// A range that bounds something: a quantity's {min, max, not}, an integer's {min, max} (an
  /// unsigned integer is >= 0 by its type).
  bool has_bound(const nlohmann::json &range)
  {
    return range.is_object() &&
           (range.contains("min") || range.contains("max") || range.contains("not"));
  }

  /// Counts the numeric keys and collects the paths of those without a bound, walking sections,
  /// list items and map values.
  void walk(const nlohmann::json &keys, std::size_t &n_numeric, std::vector<std::string> &unbounded)
  {
    for (const nlohmann::json &key : keys)
    {
      const std::string type = key.at("type");
      if (is_numeric(type))
      {
        ++n_numeric;
        if (!has_bound(key.at("range")))
          unbounded.push_back(key.at("path"));
      }
      for (const char *member : {"keys", "item", "value"})
        if (key.contains(member))
          walk(key.at(member).is_array() ? key.at(member) : nlohmann::json::array({key.at(member)}),
               n_numeric,
               unbounded);
    }
  }

  std::map<std::string, std::string> schemas()
  {
    std::map<std::string, std::string> kinds{
      {"lumped", kimp::io::schema_text<kimp::app::LumpedScene>()},
      {"collide", kimp::io::schema_text<kimp::app::CollideScene>()},
      {"fit", kimp::io::schema_text<kimp::fit::FitConfig>()},
      {"export-opensees", kimp::io::schema_text<kimp::app::ExportOpenSeesSettings>()},
      {"sweep", kimp::app::sweep_file_schema_text()}};
#ifdef KIMP_WITH_FEM
    kinds["fem"]   = kimp::io::schema_text<kimp::app::FemScene>();
    kinds["study"] = kimp::io::schema_text<kimp::app::StudyScene>();
#endif
    return kinds;
  }

  TEST(SceneSchema, EveryNumericKeyDeclaresItsRange)
  {
    std::set<std::string> allowed_seen;
    std::size_t           n_numeric = 0;
    for (const auto &[kind, text] : schemas())
    {
      const nlohmann::json     schema = nlohmann::json::parse(text);
      std::vector<std::string> found;
      walk(schema.at("keys"), n_numeric, found);
      for (const std::string &path : found)
      {
        if (unbounded_keys.count(path) > 0)
          allowed_seen.insert(path);
        else
          ADD_FAILURE() << kind << ": numeric key " << path
                        << " has no range: declare it in visit() (io::Range) or, if it is truly "
                           "unbounded, list it with the reason in unbounded_keys";
      }
    }
    // The walk reaches every key: lumped alone has 80 numeric keys.
    EXPECT_GT(n_numeric, 150u);
    for (const auto &[path, why] : unbounded_keys)
      EXPECT_EQ(allowed_seen.count(path), 1u)
        << path << " (" << why << ") is listed as unbounded but is bounded or not a key: remove it";
  }

  TEST(SceneSchema, RangesReachTheDefaultsAndTheSchemaText)
  {
    // One declaration: the range printed in the listing comes from the Range, not the doc text.
    const std::string lumped = kimp::io::default_scene_text<kimp::app::LumpedScene>("lumped");
    kimp::testing::expect_contains(
      lumped,
      {"  K1: \"200 MN/m\"  # bilinear, bouc_wen: initial stiffness [MN/m, > 0]",
       "  cor: \"0.7\"  # nominal coefficient of restitution [dimensionless, in (0, 1]]",
       "  scale: \"1\"  # factor applied after scale_to_pga (negative flips it) [dimensionless, "
       "!= 0]"});
#ifdef KIMP_WITH_FEM
    const std::string fem = kimp::io::default_scene_text<kimp::app::FemScene>("fem");
    kimp::testing::expect_contains(
      fem,
      {"  end_time: \"50 ms\"  # largest simulated time [ms, > 0]",
       "  penalty_factor: \"1\"  # penalty stiffness per slave node / (E_master / h_contact x "
       "tributary length) [dimensionless, > 0]"});
    EXPECT_EQ(fem.find("(> 0)"), std::string::npos) << "a doc text repeats its range:\n" << fem;
#endif
  }

  TEST(SceneSchema, SweepEngineAndCombineAreChoices)
  {
    const nlohmann::json schema = nlohmann::json::parse(kimp::app::sweep_file_schema_text());
    std::map<std::string, nlohmann::json> by_key;
    for (const nlohmann::json &key : schema.at("keys"))
      by_key[key.at("key")] = key;
    EXPECT_EQ(by_key.at("engine").at("type"), "choice");
    EXPECT_EQ(by_key.at("engine").at("options"), nlohmann::json::array({"lumped"}));
    EXPECT_EQ(by_key.at("combine").at("type"), "choice");
    EXPECT_EQ(by_key.at("combine").at("options"), nlohmann::json::array({"product", "zip"}));
    const nlohmann::json &report_kind = by_key.at("report").at("keys").at(0);
    EXPECT_EQ(report_kind.at("key"), "kind");
    EXPECT_EQ(report_kind.at("type"), "choice");
    EXPECT_EQ(report_kind.at("options").size(), kimp::app::sweep_report_kinds().size());
  }
} // namespace
