// The two JSON Ios of a scene (see scene_io.h): JsonWriter (the resolved values in SI, for
// /input/resolved and the study cache keys) and SchemaWriter (the keys with type, unit, default,
// range and doc, for `--print-schema` and the forms generated from it).
#pragma once

#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/scene_source.h"
#include "io/scene_verbs.h"

namespace kimp::io
{
  /// Io that builds a JSON object of the current values in SI (quantities as plain numbers).
  class JsonWriter : public IoVerbs<JsonWriter>
  {
  public:
    JsonWriter();
    JsonWriter(JsonWriter &&) noexcept;
    ~JsonWriter();

    /// The JSON text of everything written so far.
    std::string dump(int indent = 2) const;

    /// Sets the key to its value in SI (a choice as its name, a YAML text as JSON).
    void value(const Key &key, Member::Ref member);

    /// The writer of the object at `key`.
    std::optional<JsonWriter> open_section(std::string_view key, std::string_view doc);

    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      if (value)
        section(key, *value, doc);
      else
        null(key);
    }

    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view /*doc*/)
    {
      empty_array(key);
      for (T &item : values)
      {
        JsonWriter sub = array_item(key);
        visit(sub, item);
      }
    }

    /// An object of the entries, in order.
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      JsonWriter sub = object(key);
      for (auto &[name, value] : entries)
        detail::visit_map_value(sub, name, value, doc);
    }

  private:
    JsonWriter(std::shared_ptr<nlohmann::ordered_json> root, nlohmann::ordered_json *node);

    JsonWriter object(std::string_view key);
    void       null(std::string_view key);
    void       empty_array(std::string_view key);
    JsonWriter array_item(std::string_view key);

    std::shared_ptr<nlohmann::ordered_json> root_; ///< owns the document
    nlohmann::ordered_json                 *node_; ///< the object this writer fills
  };

  /// JSON text of `value` (SI numbers) through its visit(); a compact line for `indent` < 0.
  template <class T>
  std::string to_json_text(const T &value, int indent = 2)
  {
    T          copy = value;
    JsonWriter writer;
    visit(writer, copy);
    return writer.dump(indent);
  }

  /**
   * Io that describes the keys a visit() walks, as JSON for form generators: an array of
   * {key, path, type, unit, default, range, doc} entries in file order. Types: "quantity" (default
   * as the file would write it, e.g. "15 cm", and `default_si`), "quantity_list", "optional
   * quantity", "integer" (range {min, max}), "flag", "text", "choice" (with `options`), "section"
   * and "optional section" (with `keys`), "list" (with `item`: the keys of one item, and
   * `default`: the default items as resolved JSON). A quantity's range is
   * {min, min_open, max, max_open} in SI (`not: 0` for io::Range::nonzero()) plus `text` in the
   * display unit, or null when the quantity has no bound.
   */
  class SchemaWriter : public IoVerbs<SchemaWriter>
  {
  public:
    SchemaWriter();
    SchemaWriter(SchemaWriter &&) noexcept;
    ~SchemaWriter();

    /// The JSON text of the schema: {"keys": [...]}.
    std::string dump(int indent = 2) const;

    /// Appends the key's entry: type, doc, default and, by kind, unit and range or options.
    void value(const Key &key, Member::Ref member);

    /// Appends a "section" entry and returns the writer of its keys.
    std::optional<SchemaWriter> open_section(std::string_view key, std::string_view doc);

    /// Its `default` is the resolved JSON of the default value, or null when absent.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view doc)
    {
      SchemaWriter sub =
        nested(key, "optional section", doc, "keys", value ? to_json_text(*value, -1) : "null");
      T example = value ? *value : T();
      visit(sub, example);
    }

    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view doc)
    {
      std::string items;
      for (const T &item : values)
        items += (items.empty() ? "" : ",") + to_json_text(item, -1);
      SchemaWriter sub = nested(key, "list", doc, "item", "[" + items + "]");
      T            example;
      visit(sub, example);
    }

    /// Type "map" with `value`: the entry of one value, keyed "<name>".
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      std::string items;
      for (const auto &[name, value] : entries)
        items += (items.empty() ? "" : ",") + json_string(name) + ":" + map_value_json(value);
      SchemaWriter sub = nested(key, "map", doc, "value", "{" + items + "}");
      T            example;
      detail::visit_map_value(sub, "<name>", example, doc);
    }

  private:
    /// `text` as a JSON string literal.
    static std::string json_string(const std::string &text);
    /// JSON of a raw YAML text (scalars as strings).
    static std::string yaml_json(const std::string &yaml_text);
    template <class T>
    static std::string map_value_json(const T &value)
    {
      if constexpr (std::is_same_v<T, std::string>)
        return yaml_json(value);
      else
        return to_json_text(value, -1);
    }

    struct State;
    explicit SchemaWriter(std::unique_ptr<State> state);

    /// Appends an entry of `type` (with `default_json` as its default unless empty) and returns a
    /// writer of its `member` array.
    SchemaWriter nested(std::string_view   key,
                        std::string_view   type,
                        std::string_view   doc,
                        std::string_view   member,
                        const std::string &default_json);

    std::unique_ptr<State> state_;
  };
} // namespace kimp::io
