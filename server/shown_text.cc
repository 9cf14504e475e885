// Quoting, clipping and folder-relative paths of the text `kimp gui` shows (server/shown_text.h).
#include "server/shown_text.h"

#include <algorithm>
#include <cctype>
#include <system_error>

namespace kimp::server
{
  namespace
  {
    /// Whether `c` can continue a file name (a folder path followed by it is another path).
    bool name_char(char c)
    {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    }
  } // namespace

  std::string clipped(std::string_view value)
  {
    if (value.size() <= quoted_max)
      return std::string(value);
    return std::string(value.substr(0, quoted_max)) + "... (" + std::to_string(value.size()) +
           " bytes)";
  }

  std::string in_quotes(std::string_view value)
  {
    if (value.size() <= quoted_max)
      return "\"" + std::string(value) + "\"";
    return "\"" + std::string(value.substr(0, quoted_max)) + "\"... (" +
           std::to_string(value.size()) + " bytes)";
  }

  std::string clip_long_lines(std::string text)
  {
    constexpr std::size_t longest_word = 100;
    std::string           words;
    words.reserve(std::min<std::size_t>(text.size(), 1u << 16));
    for (std::size_t start = 0; start <= text.size();)
    {
      std::size_t end = text.find_first_of(" \n", start);
      if (end == std::string::npos)
        end = text.size();
      const std::string_view word = std::string_view(text).substr(start, end - start);
      if (word.size() > longest_word)
        words += clipped(word);
      else
        words += word;
      if (end < text.size())
        words += text[end];
      start = end + 1;
    }
    text                          = std::move(words);
    constexpr std::size_t longest = 240, head = 100, tail = 60;
    std::string           out;
    std::size_t           start = 0;
    while (start <= text.size())
    {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos)
        end = text.size();
      const std::size_t size = end - start;
      if (size > longest)
        out.append(text, start, head)
          .append(" [... " + std::to_string(size - head - tail) + " bytes left out ...] ")
          .append(text, end - tail, tail);
      else
        out.append(text, start, size);
      if (end == text.size())
        break;
      out += '\n';
      start = end + 1;
    }
    return out;
  }

  FolderPaths::FolderPaths(const std::filesystem::path                &runs_dir,
                           const std::optional<std::filesystem::path> &records_dir)
  {
    const auto add = [this](const std::filesystem::path &folder)
    {
      std::error_code ec;
      const auto      name = folder_name(folder);
      for (std::filesystem::path spelling :
           {std::filesystem::absolute(folder, ec), std::filesystem::weakly_canonical(folder, ec)})
      {
        std::string text = spelling.lexically_normal().string();
        while (text.size() > 1 && text.back() == '/')
          text.pop_back();
        // A folder at the root ("/") would turn every path into a name.
        if (text.size() > 1 && text.front() == '/')
          folders_.emplace_back(text, name);
      }
    };
    add(runs_dir);
    if (records_dir)
      add(*records_dir);
    std::sort(folders_.begin(),
              folders_.end(),
              [](const auto &a, const auto &b) { return a.first.size() > b.first.size(); });
  }

  std::string FolderPaths::folder_name(const std::filesystem::path &folder)
  {
    const std::filesystem::path normal = folder.lexically_normal();
    std::string name = (normal.has_filename() ? normal : normal.parent_path()).filename().string();
    if (name.empty() || name == "." || name == "..")
    {
      std::error_code ec;
      name = std::filesystem::weakly_canonical(folder, ec).filename().string();
    }
    return name;
  }

  std::string FolderPaths::operator()(std::string text) const
  {
    return clip_long_lines(relative(std::move(text)));
  }

  std::string FolderPaths::relative(std::string text) const
  {
    for (const auto &[path, name] : folders_)
      for (std::size_t at = text.find(path); at != std::string::npos; at = text.find(path, at))
      {
        const std::size_t after = at + path.size();
        if (at > 0 && name_char(text[at - 1]))
        {
          at = after;
          continue;
        }
        if (after < text.size() && text[after] == '/')
          text.erase(at, path.size() + 1);
        else if (after == text.size() || !name_char(text[after]))
        {
          text.replace(at, path.size(), name);
          at += name.size();
        }
        else
          at = after;
      }
    return text;
  }
} // namespace kimp::server
