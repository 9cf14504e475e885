// DefaultsPrinter: the Io that writes the annotated default scene of `--print-defaults`
// (see scene_io.h).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/scene_source.h"
#include "io/scene_verbs.h"

namespace kimp::io
{
  /**
   * Io that writes an annotated YAML scene of the current values (the defaults when given a
   * default-constructed struct): every key, its value in the display unit and a comment with
   * meaning, unit and admissible range (the range printed from the key's io::Range, so a doc text
   * need not repeat it). Reading the output back gives the same values.
   */
  class DefaultsPrinter : public IoVerbs<DefaultsPrinter>
  {
  public:
    explicit DefaultsPrinter(std::ostream &out);

    /// Writes the key, its value and a comment with meaning, unit, range or options.
    void value(const Key &key, Member::Ref member);

    /// Writes the section's key and returns the printer of its keys.
    std::optional<DefaultsPrinter> open_section(std::string_view key, std::string_view doc);

    /// An absent optional section is listed commented out, with the defaults of T.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      if (value)
      {
        section(key, *value, std::string(doc) + " (optional)");
        return;
      }
      line(key, "", std::string(doc) + " (optional; absent by default, example below)", "# ");
      DefaultsPrinter sub = child(lead_ + "#   ", "");
      T               example;
      visit(sub, example);
    }

    /// A list prints its default items; an empty list prints `[]` and one commented example item.
    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view doc)
    {
      if (values.empty())
      {
        line(key, "[]", std::string(doc) + " (list; example item below)");
        DefaultsPrinter sub = child(lead_ + "#     ", lead_ + "#   - ");
        T               example;
        visit(sub, example);
        return;
      }
      line(key, "", std::string(doc) + " (list)");
      for (T &item : values)
      {
        DefaultsPrinter sub = child(lead_ + "    ", lead_ + "  - ");
        visit(sub, item);
      }
    }

    /// Every entry under `key` (`{}` when there is none).
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      if (entries.empty())
      {
        line(key, "{}", std::string(doc) + " (map)");
        return;
      }
      line(key, "", std::string(doc) + " (map)");
      DefaultsPrinter sub = child(lead_ + "  ", "");
      for (auto &[name, value] : entries)
        detail::visit_map_value(sub, name, value, ""); // the map's comment says what they are
    }

  private:
    DefaultsPrinter child(std::string lead, std::string first_lead) const;
    /// `key: value  # comment` (no comment when it is empty).
    void line(std::string_view key,
              std::string_view value,
              std::string_view comment,
              std::string_view extra_lead = "");

    std::ostream *out_;
    std::string   lead_;       ///< text before every key of this map (indentation, "# ")
    std::string   first_lead_; ///< lead of the first key of a list item ("  - "), then lead_
  };
} // namespace kimp::io
