// The resolved JSON of a scene and its key schema; see scene_json.h.
#include "io/scene_json.h"

#include <climits>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <variant>
#include <yaml-cpp/yaml.h>

#include "io/units.h"

namespace kimp::io
{
  using detail::integer_range_text;

  namespace
  {
    /// JSON of a YAML value; scalars stay strings (their type is the caller's to decide).
    nlohmann::ordered_json yaml_to_json(const YAML::Node &node)
    {
      if (!node.IsDefined() || node.IsNull())
        return nullptr;
      if (node.IsScalar())
        return node.Scalar();
      nlohmann::ordered_json json =
        node.IsSequence() ? nlohmann::ordered_json::array() : nlohmann::ordered_json::object();
      for (auto it = node.begin(); it != node.end(); ++it)
        if (node.IsSequence())
          json.push_back(yaml_to_json(*it));
        else
          json[it->first.as<std::string>()] = yaml_to_json(it->second);
      return json;
    }

    nlohmann::ordered_json yaml_text_to_json(const std::string &yaml_text)
    {
      return yaml_text.empty() ? nlohmann::ordered_json(nullptr) :
                                 yaml_to_json(YAML::Load(yaml_text));
    }
  } // namespace

  JsonWriter::JsonWriter()
    : root_(std::make_shared<nlohmann::ordered_json>(nlohmann::ordered_json::object()))
    , node_(root_.get())
  {
  }

  JsonWriter::JsonWriter(std::shared_ptr<nlohmann::ordered_json> root, nlohmann::ordered_json *node)
    : root_(std::move(root))
    , node_(node)
  {
  }

  JsonWriter::JsonWriter(JsonWriter &&) noexcept = default;
  JsonWriter::~JsonWriter()                      = default;

  std::string JsonWriter::dump(int indent) const
  {
    // Scene text may hold bytes that are not UTF-8 (a mistyped or binary file): replaced
    // (U+FFFD) rather than thrown, so a bad scene is refused by its reader, not by the JSON writer.
    return root_->dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  namespace
  {
    nlohmann::ordered_json json_of(const double *value)
    {
      return *value;
    }
    nlohmann::ordered_json json_of(const std::optional<double> *value)
    {
      return *value ? nlohmann::ordered_json(**value) : nlohmann::ordered_json(nullptr);
    }
    nlohmann::ordered_json json_of(const std::vector<double> *values)
    {
      return *values;
    }
    nlohmann::ordered_json json_of(const bool *value)
    {
      return *value;
    }
    nlohmann::ordered_json json_of(Member::Text member)
    {
      return *member.value;
    }
    nlohmann::ordered_json json_of(Member::Yaml member)
    {
      return yaml_text_to_json(*member.text);
    }
    nlohmann::ordered_json json_of(Member::Integer member)
    {
      return *member.value;
    }
    nlohmann::ordered_json json_of(Member::Choice member)
    {
      return member.options->at(*member.index);
    }
  } // namespace

  void JsonWriter::value(const Key &key, Member::Ref member)
  {
    (*node_)[std::string(key.key)] = std::visit([](auto m) { return json_of(m); }, member);
  }

  std::optional<JsonWriter> JsonWriter::open_section(std::string_view key, std::string_view /*doc*/)
  {
    return object(key);
  }

  JsonWriter JsonWriter::object(std::string_view key)
  {
    nlohmann::ordered_json &child = (*node_)[std::string(key)];
    child                         = nlohmann::ordered_json::object();
    return JsonWriter(root_, &child);
  }

  void JsonWriter::null(std::string_view key)
  {
    (*node_)[std::string(key)] = nullptr;
  }

  void JsonWriter::empty_array(std::string_view key)
  {
    (*node_)[std::string(key)] = nlohmann::ordered_json::array();
  }

  JsonWriter JsonWriter::array_item(std::string_view key)
  {
    nlohmann::ordered_json &array = (*node_)[std::string(key)];
    array.push_back(nlohmann::ordered_json::object());
    return JsonWriter(root_, &array.back());
  }

  // ---------------------------------------------------------------------------------------------

  struct SchemaWriter::State
  {
    std::shared_ptr<nlohmann::ordered_json> root;  ///< {"keys": [...]}
    nlohmann::ordered_json                 *array; ///< the entries this writer appends to
    std::string                             path;  ///< key path of this map ("" at the root)

    std::string full_path(std::string_view key) const
    {
      return path.empty() ? std::string(key) : path + "." + std::string(key);
    }

    /// Appends {key, path, type, ...} and returns it for the caller to complete.
    nlohmann::ordered_json &add(std::string_view key, std::string_view type, std::string_view doc)
    {
      nlohmann::ordered_json entry = nlohmann::ordered_json::object();
      entry["key"]                 = std::string(key);
      entry["path"]                = full_path(key);
      entry["type"]                = std::string(type);
      entry["doc"]                 = std::string(doc);
      array->push_back(std::move(entry));
      return array->back();
    }
  };

  namespace
  {
    nlohmann::ordered_json range_json(const Range &range, std::string_view unit)
    {
      if (!range.bounded())
        return nullptr;
      nlohmann::ordered_json json = nlohmann::ordered_json::object();
      if (range.min())
      {
        json["min"]      = *range.min();
        json["min_open"] = range.min_open();
      }
      if (range.max())
      {
        json["max"]      = *range.max();
        json["max_open"] = range.max_open();
      }
      if (range.excludes_zero())
        json["not"] = 0.0;
      json["text"] = range.text(unit);
      return json;
    }
  } // namespace

  SchemaWriter::SchemaWriter()
    : state_(std::make_unique<State>())
  {
    state_->root = std::make_shared<nlohmann::ordered_json>(nlohmann::ordered_json::object());
    (*state_->root)["keys"] = nlohmann::ordered_json::array();
    state_->array           = &(*state_->root)["keys"];
  }

  SchemaWriter::SchemaWriter(std::unique_ptr<State> state)
    : state_(std::move(state))
  {
  }

  SchemaWriter::SchemaWriter(SchemaWriter &&) noexcept = default;
  SchemaWriter::~SchemaWriter()                        = default;

  std::string SchemaWriter::dump(int indent) const
  {
    return state_->root->dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }

  namespace
  {
    /// Completes a key's entry by the kind of its member: its type, default and what else the
    /// kind has (a quantity's unit and range, an integer's bounds, a choice's options).
    struct Describe
    {
      const Key              &key;
      nlohmann::ordered_json &entry;

      void quantity(const char *type, nlohmann::ordered_json text, nlohmann::ordered_json si) const
      {
        entry["type"]       = type;
        entry["unit"]       = std::string(key.unit);
        entry["default"]    = std::move(text);
        entry["default_si"] = std::move(si);
        entry["range"]      = range_json(key.range, key.unit);
      }

      void operator()(const double *value) const
      {
        quantity("quantity", format_quantity(*value, key.unit), *value);
      }
      void operator()(const std::optional<double> *value) const
      {
        quantity("optional quantity",
                 *value ? nlohmann::ordered_json(format_quantity(**value, key.unit)) : nullptr,
                 *value ? nlohmann::ordered_json(**value) : nullptr);
      }
      void operator()(const std::vector<double> *values) const
      {
        std::vector<std::string> texts;
        for (const double v : *values)
          texts.push_back(format_quantity(v, key.unit));
        quantity("quantity_list", texts, *values);
      }
      void operator()(const bool *value) const
      {
        entry["type"]    = "flag";
        entry["default"] = *value;
      }
      void operator()(Member::Text member) const
      {
        entry["type"]    = "text";
        entry["default"] = *member.value;
        // A quantity typed as text (IoVerbs::quantity_text): its unit and range too.
        if (key.range.bounded())
        {
          entry["unit"]  = std::string(key.unit);
          entry["range"] = range_json(key.range, key.unit);
        }
      }
      void operator()(Member::Yaml member) const
      {
        entry["type"]    = "yaml";
        entry["default"] = *member.text;
      }
      void operator()(Member::Integer member) const
      {
        entry["type"]                = "integer";
        entry["default"]             = *member.value;
        nlohmann::ordered_json range = nlohmann::ordered_json::object();
        // Bounds at or beyond the range of int are type limits, as in the default listing.
        if (member.min > INT_MIN)
          range["min"] = member.min;
        if (member.max < INT_MAX)
          range["max"] = member.max;
        range["text"]  = integer_range_text(member.min, member.max);
        entry["range"] = range;
      }
      void operator()(Member::Choice member) const
      {
        entry["type"]    = "choice";
        entry["default"] = member.options->at(*member.index);
        entry["options"] = *member.options;
      }
    };
  } // namespace

  void SchemaWriter::value(const Key &key, Member::Ref member)
  {
    std::visit(Describe{key, state_->add(key.key, "", key.doc)}, member);
  }

  std::optional<SchemaWriter> SchemaWriter::open_section(std::string_view key, std::string_view doc)
  {
    return nested(key, "section", doc, "keys", "");
  }

  std::string SchemaWriter::json_string(const std::string &text)
  {
    return nlohmann::ordered_json(text).dump(-1,
                                             ' ',
                                             false,
                                             nlohmann::ordered_json::error_handler_t::replace);
  }

  std::string SchemaWriter::yaml_json(const std::string &yaml_text)
  {
    return yaml_text_to_json(yaml_text).dump(-1,
                                             ' ',
                                             false,
                                             nlohmann::ordered_json::error_handler_t::replace);
  }

  SchemaWriter SchemaWriter::nested(std::string_view   key,
                                    std::string_view   type,
                                    std::string_view   doc,
                                    std::string_view   member,
                                    const std::string &default_json)
  {
    nlohmann::ordered_json &entry = state_->add(key, type, doc);
    if (!default_json.empty())
      entry["default"] = nlohmann::ordered_json::parse(default_json);
    // The entry is complete before the child writer points into it (ordered_json objects
    // reallocate when a key is added).
    nlohmann::ordered_json &keys = entry[std::string(member)];
    keys                         = nlohmann::ordered_json::array();
    auto sub                     = std::make_unique<State>();
    sub->root                    = state_->root;
    sub->array                   = &keys;
    sub->path = state_->full_path(key) + (member == "item" ? std::string("[]") : std::string());
    return SchemaWriter(std::move(sub));
  }
} // namespace kimp::io
