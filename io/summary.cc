// Atomic writes of summary.json / CSV and the output directory; see summary.h.
#include "io/summary.h"

#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>
#include <unistd.h>

namespace kimp::io
{
  namespace
  {
    std::string csv_field(const std::string &field)
    {
      if (field.find_first_of(",\"\r\n") == std::string::npos)
        return field;
      std::string quoted = "\"";
      for (const char c : field)
      {
        if (c == '"')
          quoted += '"';
        quoted += c;
      }
      return quoted + "\"";
    }

    std::string csv_text(const std::filesystem::path                 &path,
                         const std::vector<std::string>              &header,
                         const std::vector<std::vector<std::string>> &rows)
    {
      std::string text;
      const auto  add_row = [&text](const std::vector<std::string> &fields)
      {
        for (std::size_t i = 0; i < fields.size(); ++i)
        {
          if (i > 0)
            text += ',';
          text += csv_field(fields[i]);
        }
        text += '\n';
      };
      add_row(header);
      for (std::size_t r = 0; r < rows.size(); ++r)
      {
        if (rows[r].size() != header.size())
          throw OutputError(fmt::format("{}: CSV row {} has {} fields, the header has {}",
                                        path.string(),
                                        r + 1,
                                        rows[r].size(),
                                        header.size()));
        add_row(rows[r]);
      }
      return text;
    }
  } // namespace

  void write_text_atomic(const std::filesystem::path &path, std::string_view text)
  {
    const std::filesystem::path temporary = path.string() + ".tmp-" + std::to_string(::getpid());
    std::error_code             ignored;
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out)
        throw OutputError(
          fmt::format("{}: cannot create '{}' for writing", path.string(), temporary.string()));
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      out.close();
      if (!out)
      {
        std::filesystem::remove(temporary, ignored);
        throw OutputError(
          fmt::format("{}: writing '{}' failed (disk full?)", path.string(), temporary.string()));
      }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
    {
      std::filesystem::remove(temporary, ignored);
      throw OutputError(fmt::format("{}: renaming '{}' to it failed: {}",
                                    path.string(),
                                    temporary.string(),
                                    error.message()));
    }
  }

  void write_json_atomic(const std::filesystem::path &path, const nlohmann::json &value)
  {
    write_text_atomic(path, value.dump(2) + "\n");
  }

  void write_csv_atomic(const std::filesystem::path                 &path,
                        const std::vector<std::string>              &header,
                        const std::vector<std::vector<std::string>> &rows)
  {
    write_text_atomic(path, csv_text(path, header, rows));
  }

  void write_csv_atomic(const std::filesystem::path            &path,
                        const std::vector<std::string>         &header,
                        const std::vector<std::vector<double>> &rows)
  {
    std::vector<std::vector<std::string>> text_rows;
    text_rows.reserve(rows.size());
    for (const auto &row : rows)
    {
      std::vector<std::string> fields;
      fields.reserve(row.size());
      for (const double v : row)
        fields.push_back(fmt::format("{}", v));
      text_rows.push_back(std::move(fields));
    }
    write_csv_atomic(path, header, text_rows);
  }

  OutputDir::OutputDir(std::filesystem::path path)
    : path_(std::move(path))
  {
    std::error_code error;
    if (std::filesystem::exists(path_, error) && !std::filesystem::is_directory(path_, error))
      throw OutputError(
        fmt::format("output directory '{}' exists and is not a directory", path_.string()));
    std::filesystem::create_directories(path_, error);
    if (error)
      throw OutputError(
        fmt::format("cannot create output directory '{}': {}", path_.string(), error.message()));
  }

  std::filesystem::path OutputDir::file(const std::filesystem::path &name) const
  {
    const std::filesystem::path full = path_ / name;
    if (full.has_parent_path() && full.parent_path() != path_)
    {
      std::error_code error;
      std::filesystem::create_directories(full.parent_path(), error);
      if (error)
        throw OutputError(fmt::format("cannot create directory '{}': {}",
                                      full.parent_path().string(),
                                      error.message()));
    }
    return full;
  }
} // namespace kimp::io
