// SceneReader: the Io that reads one YAML map of a scene file into a struct (see scene_io.h).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/scene_source.h"
#include "io/scene_verbs.h"

namespace kimp::io
{
  /**
   * Io that reads one YAML map into a struct. Keys missing from the file keep the struct's
   * defaults; every key present is recorded with its line in the SceneSource; finish() rejects
   * keys that no verb asked for. Errors throw SceneError; a value outside its range is recorded
   * in the SceneSource and reported with validate()'s failures.
   */
  class SceneReader : public IoVerbs<SceneReader>
  {
  public:
    /// Reader of the document root of `text` (an empty document reads as an empty map).
    static SceneReader root(const std::string &text, SceneSource &source);

    SceneReader(SceneReader &&) noexcept;
    SceneReader &operator=(SceneReader &&) noexcept;
    ~SceneReader();

    using IoVerbs<SceneReader>::section;

    void quantity_value(const QuantityKey &key, double &value);
    void quantity_value(const QuantityKey &key, std::optional<double> &value);
    void quantity_value(const QuantityKey &key, std::vector<double> &values);
    void flag(std::string_view key, bool &value, std::string_view doc);
    void text(std::string_view key, std::string &value, std::string_view doc);

    /// A section whose keys `visit_keys(io, value)` declares.
    template <class T, class VisitKeys>
    void section(std::string_view key, T &value, std::string_view /*doc*/, VisitKeys visit_keys)
    {
      if (std::optional<SceneReader> sub = open_section(key, false))
      {
        visit_keys(*sub, value);
        sub->finish();
      }
    }

    /// Optional section: absent keeps the default, `null` clears it, a map fills a default T.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view /*doc*/)
    {
      if (!has_key(key))
        return;
      std::optional<SceneReader> sub = open_section(key, true);
      if (!sub)
      {
        value.reset();
        return;
      }
      value.emplace();
      visit(*sub, *value);
      sub->finish();
    }

    /// List of sections (`- key: value` items), replacing the default list when present.
    template <class T>
    void list(std::string_view key, std::vector<T> &values, std::string_view /*doc*/)
    {
      const std::optional<std::size_t> n = open_list(key);
      if (!n)
        return;
      values.clear();
      for (std::size_t i = 0; i < *n; ++i)
      {
        SceneReader item = list_item(key, i);
        T           value;
        visit(item, value);
        item.finish();
        values.push_back(std::move(value));
      }
    }

    /**
     * Any YAML value (scalar, list or map) kept as one line of flow-style YAML text, for a caller
     * that interprets it itself (e.g. a sweep's list of values or {from, to, step}); `null` gives
     * "~". The lines of its items are recorded in the SceneSource as "key[i]" and "key.sub".
     */
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc);

    /**
     * Map whose keys the file chooses (e.g. scene key paths), in file order, replacing the default
     * entries when present. A std::string value is read with raw(), any other T as a section.
     */
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      std::optional<SceneReader> sub = open_map(key);
      if (!sub)
        return;
      entries.clear();
      for (const std::string &name : sub->keys())
      {
        T value;
        detail::visit_map_value(*sub, name, value, doc);
        entries.emplace_back(name, std::move(value));
      }
      sub->finish();
    }

    /// Rejects every key of this map that no verb asked for (thrown, with those of all nested
    /// maps, when the root reader finishes).
    void finish();

    void integer_value(std::string_view key,
                       long long       &value,
                       std::string_view doc,
                       long long        min,
                       long long        max);
    void choice_index(std::string_view                key,
                      std::size_t                    &index,
                      const std::vector<std::string> &options,
                      std::string_view                doc);

  private:
    struct State;
    explicit SceneReader(std::unique_ptr<State> state);

    bool                       has_key(std::string_view key) const;
    std::optional<SceneReader> open_section(std::string_view key, bool null_means_absent);
    std::optional<std::size_t> open_list(std::string_view key);
    SceneReader                list_item(std::string_view key, std::size_t index);
    std::optional<SceneReader> open_map(std::string_view key);
    std::vector<std::string>   keys() const;

    std::unique_ptr<State> state_;
  };
} // namespace kimp::io
