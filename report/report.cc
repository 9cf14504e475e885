// Result directory -> report data (JSON) -> one self-contained HTML page (report/report.h).
#include "report/report.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "io/results_json.h"
#include "io/summary.h"

#include "report/assets.h"

namespace kimp::report
{
  std::optional<std::string_view> asset(std::string_view name)
  {
    for (const detail::EmbeddedAsset *a = detail::embedded_assets; a->name != nullptr; ++a)
      if (name == a->name)
        return std::string_view(a->bytes, a->size);
    return std::nullopt;
  }

  std::vector<std::string_view> asset_names()
  {
    std::vector<std::string_view> names;
    for (const detail::EmbeddedAsset *a = detail::embedded_assets; a->name != nullptr; ++a)
      names.emplace_back(a->name);
    return names;
  }

  namespace
  {
    std::string read_file(const std::filesystem::path &path)
    {
      std::ifstream      in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    }

    /// Seven significant digits are far below what a chart or a CSV export of a chart shows,
    /// and keep the report a few MB instead of tens. std::to_chars and std::from_chars give
    /// what "%.7g" and strtod give, several times faster (a 17 MB result holds millions of
    /// numbers, and kimp gui rounds them for every request of its data).
    void round_values(nlohmann::json &value)
    {
      if (value.is_number_float())
      {
        const double x = value.get<double>();
        if (std::isfinite(x))
        {
          char       text[32];
          const auto end =
            std::to_chars(text, text + sizeof(text), x, std::chars_format::general, 7).ptr;
          double rounded = x;
          std::from_chars(text, end, rounded);
          value = rounded;
        }
        else
          value = nullptr;
      }
      else if (value.is_array() || value.is_object())
        for (auto &item : value)
          round_values(item);
    }

    void replace_all(std::string &text, std::string_view from, std::string_view to)
    {
      for (std::size_t at = text.find(from); at != std::string::npos;
           at             = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    }

    std::string required_asset(std::string_view name)
    {
      const auto text = asset(name);
      if (!text)
        throw std::logic_error("embedded page file missing: " + std::string(name));
      return std::string(*text);
    }

    /// Inline text inside <script>: a literal "</script" would end the element early.
    std::string script_safe(std::string text)
    {
      replace_all(text, "</script", "<\\/script");
      return text;
    }
  } // namespace

  nlohmann::json report_data(const std::filesystem::path &dir)
  {
    if (!std::filesystem::is_directory(dir))
      throw std::invalid_argument(dir.string() + ": not a directory (expected a result directory)");
    nlohmann::json data;
    std::string    title = std::filesystem::absolute(dir).lexically_normal().filename().string();
    if (title.empty())
      title = std::filesystem::absolute(dir).lexically_normal().parent_path().filename().string();
    data["title"] = title;
    data["kind"]  = "";
    data["csv"]   = nlohmann::json::object();
    data["h5"]    = nlohmann::json::object();
    for (const char *kind : {"study", "sweep", "lumped", "collide", "fit", "fem"})
      if (std::filesystem::exists(dir / (std::string(kind) + ".h5")))
      {
        data["kind"] = kind;
        break;
      }
    std::vector<std::filesystem::path> entries;
    for (const auto &entry : std::filesystem::directory_iterator(dir))
      if (entry.is_regular_file())
        entries.push_back(entry.path());
    std::sort(entries.begin(), entries.end());
    for (const auto &path : entries)
    {
      const std::string name = path.filename().string();
      if (path.extension() == ".csv")
        data["csv"][name] = read_file(path);
      else if (path.extension() == ".h5")
      {
        nlohmann::json h5 = io::results_to_json(path);
        round_values(h5["datasets"]);
        data["h5"][name] = std::move(h5);
      }
    }
    const auto summary = dir / "summary.json";
    if (std::filesystem::exists(summary))
      data["summary"] = nlohmann::json::parse(read_file(summary), nullptr, false);
    if (data["h5"].empty() && !data.contains("summary"))
      throw std::invalid_argument(dir.string() +
                                  ": no results file (*.h5) nor summary.json (expected the output "
                                  "directory of kimp lumped, collide, fem, fit, study or sweep)");
    // `kimp export-opensees`: its results are the OpenSees input files, shown as they are.
    if (data.contains("summary") && data["summary"].is_object() &&
        data["summary"].value("command", "") == "export-opensees")
    {
      data["kind"] = "export-opensees";
      data["text"] = nlohmann::json::object();
      for (const char *name : {"opensees_impact.tcl", "opensees_impact.py"})
        if (std::filesystem::exists(dir / name))
          data["text"][name] = read_file(dir / name);
      if (data["text"].empty())
        throw std::invalid_argument(dir.string() +
                                    ": an export-opensees directory without its files "
                                    "opensees_impact.tcl and opensees_impact.py");
    }
    return data;
  }

  std::string report_html(const nlohmann::json &data)
  {
    std::string page = required_asset("report.html");
    std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    replace_all(json, "</", "<\\/");
    // Substitute the data last so that nothing inside it is taken for a placeholder.
    replace_all(page,
                "/*KIMP_STYLE*/",
                required_asset("uPlot.min.css") + required_asset("style.css"));
    replace_all(page, "/*KIMP_UPLOT*/", script_safe(required_asset("uPlot.iife.min.js")));
    replace_all(page, "/*KIMP_PAGE*/", script_safe(required_asset("kimp.js")));
    const std::string marker = "/*KIMP_DATA*/";
    const std::size_t at     = page.find(marker);
    if (at == std::string::npos)
      throw std::logic_error("report.html has no data placeholder");
    page.replace(at, marker.size(), json);
    return page;
  }

  std::filesystem::path write_report(const std::filesystem::path &dir,
                                     const std::filesystem::path &output)
  {
    const std::filesystem::path path = output.empty() ? dir / "report.html" : output;
    io::write_text_atomic(path, report_html(report_data(dir)));
    return path;
  }

  std::string gui_html()
  {
    return required_asset("gui.html");
  }
} // namespace kimp::report
