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

    /// Reads the key's value into `member` (absent: keeps it).
    void value(const Key &key, Member::Ref member);

    /// The reader of section `key`, or none when the key is absent.
    std::optional<SceneReader> open_section(std::string_view key, std::string_view doc);

    /// Optional section: absent keeps the default, `null` clears it, a map fills a default T.
    template <class T>
    void optional_section(std::string_view key, std::optional<T> &value, std::string_view /*doc*/)
    {
      if (!has_key(key))
        return;
      std::optional<SceneReader> sub = open_map(key, true, false);
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
     * Map whose keys the file chooses (e.g. scene key paths), in file order, replacing the default
     * entries when present. A std::string value is read with raw(), any other T as a section.
     */
    template <class T>
    void map_of(std::string_view                        key,
                std::vector<std::pair<std::string, T>> &entries,
                std::string_view                        doc)
    {
      std::optional<SceneReader> sub = open_map(key, false, true);
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

  private:
    struct State;
    explicit SceneReader(std::unique_ptr<State> state);

    bool has_key(std::string_view key) const;
    /// The reader of the map at `key`, none when absent (or null, with `null_means_absent`);
    /// `file_named_keys`: a map_of() (keys chosen by the file), else a section.
    std::optional<SceneReader>
    open_map(std::string_view key, bool null_means_absent, bool file_named_keys);
    std::optional<std::size_t> open_list(std::string_view key);
    SceneReader                list_item(std::string_view key, std::size_t index);
    std::vector<std::string>   keys() const;

    std::unique_ptr<State> state_;
  };
} // namespace kimp::io
