// The resolved JSON of a scene and its key schema; see scene_json.h.
#include "io/scene_json.h"

#include <climits>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
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

  void JsonWriter::quantity_value(const QuantityKey &key, double &value)
  {
    (*node_)[std::string(key.key)] = value;
  }

  void JsonWriter::quantity_value(const QuantityKey &key, std::optional<double> &value)
  {
    (*node_)[std::string(key.key)] =
      value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
  }

  void JsonWriter::quantity_value(const QuantityKey &key, std::vector<double> &values)
  {
    (*node_)[std::string(key.key)] = values;
  }

  void JsonWriter::flag(std::string_view key, bool &value, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::text(std::string_view key, std::string &value, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::raw(std::string_view key, std::string &yaml_text, std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = yaml_text_to_json(yaml_text);
  }

  void JsonWriter::integer_value(std::string_view key,
                                 long long       &value,
                                 std::string_view /*doc*/,
                                 long long /*min*/,
                                 long long /*max*/)
  {
    (*node_)[std::string(key)] = value;
  }

  void JsonWriter::choice_index(std::string_view                key,
                                std::size_t                    &index,
                                const std::vector<std::string> &options,
                                std::string_view /*doc*/)
  {
    (*node_)[std::string(key)] = options.at(index);
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

  void SchemaWriter::add_quantity(const QuantityKey       &key,
                                  std::string_view         type,
                                  nlohmann::ordered_json &&default_text,
                                  nlohmann::ordered_json &&default_si)
  {
    nlohmann::ordered_json &entry = state_->add(key.key, type, key.doc);
    entry["unit"]                 = std::string(key.unit);
    entry["default"]              = std::move(default_text);
    entry["default_si"]           = std::move(default_si);
    entry["range"]                = range_json(key.range, key.unit);
  }

  void SchemaWriter::quantity_value(const QuantityKey &key, double &value)
  {
    add_quantity(key, "quantity", format_quantity(value, key.unit), value);
  }

  void SchemaWriter::quantity_value(const QuantityKey &key, std::optional<double> &value)
  {
    add_quantity(key,
                 "optional quantity",
                 value ? nlohmann::ordered_json(format_quantity(*value, key.unit)) : nullptr,
                 value ? nlohmann::ordered_json(*value) : nullptr);
  }

  void SchemaWriter::quantity_value(const QuantityKey &key, std::vector<double> &values)
  {
    std::vector<std::string> texts;
    for (const double v : values)
      texts.push_back(format_quantity(v, key.unit));
    add_quantity(key, "quantity_list", texts, values);
  }

  void SchemaWriter::flag(std::string_view key, bool &value, std::string_view doc)
  {
    state_->add(key, "flag", doc)["default"] = value;
  }

  void SchemaWriter::text(std::string_view key, std::string &value, std::string_view doc)
  {
    state_->add(key, "text", doc)["default"] = value;
  }

  void SchemaWriter::raw(std::string_view key, std::string &yaml_text, std::string_view doc)
  {
    state_->add(key, "yaml", doc)["default"] = yaml_text;
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

  void SchemaWriter::integer_value(std::string_view key,
                                   long long       &value,
                                   std::string_view doc,
                                   long long        min,
                                   long long        max)
  {
    nlohmann::ordered_json &entry = state_->add(key, "integer", doc);
    entry["default"]              = value;
    nlohmann::ordered_json range  = nlohmann::ordered_json::object();
    // Bounds at or beyond the range of int are type limits, as in the default listing.
    if (min > INT_MIN)
      range["min"] = min;
    if (max < INT_MAX)
      range["max"] = max;
    range["text"]  = integer_range_text(min, max);
    entry["range"] = range;
  }

  void SchemaWriter::choice_index(std::string_view                key,
                                  std::size_t                    &index,
                                  const std::vector<std::string> &options,
                                  std::string_view                doc)
  {
    nlohmann::ordered_json &entry = state_->add(key, "choice", doc);
    entry["default"]              = options.at(index);
    entry["options"]              = options;
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
