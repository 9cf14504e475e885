// Records directory resolution and record lookup by name (see records.h).
#include "io/records.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "io/at2_reader.h"
#include "io/scene_io.h"

namespace kimp::io
{
  namespace
  {
    bool directory_exists(const std::filesystem::path &path)
    {
      std::error_code ec;
      return std::filesystem::is_directory(path, ec);
    }

    bool file_exists(const std::filesystem::path &path)
    {
      std::error_code ec;
      return std::filesystem::is_regular_file(path, ec);
    }

    std::string upper(std::string s)
    {
      for (char &c : s)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      return s;
    }
  } // namespace

  std::optional<std::filesystem::path>
  resolve_records_directory(const std::optional<std::filesystem::path> &flag_value,
                            const std::optional<std::string>           &env_value,
                            const std::filesystem::path                &current_dir,
                            const std::optional<std::filesystem::path> &source_dir)
  {
    if (flag_value)
    {
      if (!directory_exists(*flag_value))
        throw std::invalid_argument("records directory = '" + flag_value->string() +
                                    "' (must be an existing directory)");
      return flag_value->lexically_normal();
    }
    if (env_value && !env_value->empty())
    {
      if (!directory_exists(*env_value))
        throw std::invalid_argument(std::string(records_dir_env_var) + " = '" + *env_value +
                                    "' (must be an existing directory)");
      return std::filesystem::path(*env_value).lexically_normal();
    }
    const std::filesystem::path from_cwd = current_dir / default_records_subpath;
    if (directory_exists(from_cwd))
      return from_cwd.lexically_normal();
    if (source_dir)
    {
      const std::filesystem::path from_source = *source_dir / default_records_subpath;
      if (directory_exists(from_source))
        return from_source.lexically_normal();
    }
    return std::nullopt;
  }

  std::optional<std::filesystem::path>
  records_directory(const std::optional<std::filesystem::path> &flag_value,
                    const std::optional<std::filesystem::path> &source_dir)
  {
    const char                *env = std::getenv(records_dir_env_var);
    std::optional<std::string> env_value;
    if (env != nullptr)
      env_value = std::string(env);
    std::error_code             ec;
    const std::filesystem::path cwd = std::filesystem::current_path(ec);
    return resolve_records_directory(flag_value, env_value, ec ? "." : cwd, source_dir);
  }

  std::optional<std::string> closest_record_name(const std::string              &name,
                                                 const std::vector<std::string> &names)
  {
    std::string given = std::filesystem::path(name).filename().string();
    if (upper(std::filesystem::path(given).extension().string()) == ".AT2")
      given = std::filesystem::path(given).stem().string();
    if (given.empty())
      return std::nullopt;
    const std::string          upper_given = upper(given);
    std::optional<std::string> best;
    std::size_t                best_distance = std::max<std::size_t>(3, given.size() / 4 + 1);
    for (const std::string &candidate : names)
    {
      const std::string upper_candidate = upper(candidate);
      // A part of the name ("KOBE", "kjm000") is a stronger hint than a few edits.
      if (upper_given.size() >= 3 && upper_candidate.find(upper_given) != std::string::npos)
        return candidate;
      if (const std::size_t d = edit_distance(upper_given, upper_candidate); d < best_distance)
      {
        best_distance = d;
        best          = candidate;
      }
    }
    return best;
  }

  std::vector<std::filesystem::path> list_records(const std::filesystem::path &directory)
  {
    std::vector<std::filesystem::path> records;
    std::error_code                    ec;
    for (const auto &entry : std::filesystem::directory_iterator(directory, ec))
      if (entry.is_regular_file(ec) && upper(entry.path().extension().string()) == ".AT2")
        records.push_back(entry.path());
    std::sort(records.begin(), records.end());
    return records;
  }

  AccelerationRecord load_record(const std::string                          &name_or_path,
                                 const std::optional<std::filesystem::path> &records_dir,
                                 std::optional<double>                       two_column_unit)
  {
    if (name_or_path.empty())
      throw std::invalid_argument("record = '' (expected a record name such as "
                                  "RSN1106_KOBE_KJM000 or a file path)");
    const std::filesystem::path given(name_or_path);
    const bool is_path = name_or_path.find('/') != std::string::npos || given.has_parent_path();
    if (is_path && !file_exists(given))
    {
      // A misspelt file name: suggest from the records beside it (or the records directory).
      std::error_code                    ec;
      const std::filesystem::path        parent = given.parent_path();
      std::vector<std::filesystem::path> files  = list_records(parent.empty() ? "." : parent);
      const bool                         beside = !files.empty();
      if (!beside && records_dir)
        files = list_records(*records_dir);
      std::vector<std::string> stems;
      for (const auto &record : files)
        stems.push_back(record.stem().string());
      std::string suggestion;
      if (const auto closest = closest_record_name(name_or_path, stems))
      {
        const auto file = std::find_if(files.begin(),
                                       files.end(),
                                       [&](const auto &f) { return f.stem() == *closest; });
        suggestion =
          "; did you mean '" + (beside ? (parent / file->filename()).string() : *closest) + "'?";
      }
      throw std::invalid_argument(
        "record = '" + name_or_path + "' is not a file (" +
        (std::filesystem::is_directory(given, ec) ? "a directory" : "no such file") +
        "; expected an AT2 or two-column record file, or a record name such as "
        "RSN1106_KOBE_KJM000 in the records directory)" +
        suggestion);
    }
    if (is_path || file_exists(given))
      return read_ground_motion(given, two_column_unit);

    if (!records_dir)
      throw std::invalid_argument(
        "record = '" + name_or_path +
        "' is a bare name but no records directory is configured (expected --records-dir, the "
        "environment variable " +
        std::string(records_dir_env_var) + " or " + default_records_subpath + ")");

    const std::vector<std::string> candidates = {name_or_path,
                                                 name_or_path + ".AT2",
                                                 name_or_path + ".at2"};
    for (const std::string &candidate : candidates)
      if (file_exists(*records_dir / candidate))
        return read_ground_motion(*records_dir / candidate, two_column_unit);

    std::string              available;
    std::vector<std::string> stems;
    for (const auto &record : list_records(*records_dir))
    {
      available += (available.empty() ? "" : ", ") + record.filename().string();
      stems.push_back(record.stem().string());
    }
    const std::optional<std::string> suggestion = closest_record_name(name_or_path, stems);
    throw std::invalid_argument(
      "record = '" + name_or_path + "' not found in '" + records_dir->string() + "' (tried " +
      candidates[0] + ", " + candidates[1] + ", " + candidates[2] +
      "; expected one of: " + (available.empty() ? std::string("<no .AT2 files>") : available) +
      ")" + (suggestion ? "; did you mean '" + *suggestion + "'?" : std::string()));
  }
} // namespace kimp::io
