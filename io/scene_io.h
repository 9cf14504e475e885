// Scene files: YAML -> plain struct with SI members -> validate() -> use (docs/architecture.md
// "Scenes and errors"). One `template <class Io> void visit(Io &, Scene &)` per struct declares
// every key once (default, unit, range, doc) and serves reading (SceneReader), the annotated
// default listing (DefaultsPrinter), the resolved JSON dump (JsonWriter) and the key schema
// (SchemaWriter). This header gathers them and holds the loaders; the pieces live in
// scene_source.h (errors, ranges, failures), scene_verbs.h (the verbs every Io shares),
// scene_reader.h, defaults_printer.h and scene_json.h.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "io/defaults_printer.h"
#include "io/scene_json.h"
#include "io/scene_reader.h"
#include "io/scene_source.h"
#include "io/scene_verbs.h"

namespace kimp::io
{
  namespace detail
  {
    template <class T, class = void>
    struct HasMemberValidate : std::false_type
    {
    };
    template <class T>
    struct HasMemberValidate<T,
                             std::void_t<decltype(std::declval<const T &>().validate(
                               std::declval<ValidationContext &>()))>> : std::true_type
    {
    };
    template <class T, class = void>
    struct HasFreeValidate : std::false_type
    {
    };
    template <class T>
    struct HasFreeValidate<T,
                           std::void_t<decltype(validate(std::declval<const T &>(),
                                                         std::declval<ValidationContext &>()))>>
      : std::true_type
    {
    };

    template <class T, class = void>
    struct HasResolvePaths : std::false_type
    {
    };
    template <class T>
    struct HasResolvePaths<
      T,
      std::void_t<decltype(resolve_paths(std::declval<T &>(),
                                         std::declval<const std::filesystem::path &>()))>>
      : std::true_type
    {
    };

  } // namespace detail

  /// A loaded scene with what the results file needs: the text verbatim and the resolved values.
  template <class T>
  struct LoadedScene
  {
    T           scene;
    std::string file_name;     ///< as given (used in messages)
    std::string text;          ///< the file verbatim, for /input/scene
    std::string resolved_json; ///< every value after defaults, SI, for /input/resolved
  };

  /// Annotated YAML of the default T: every key, default, unit and meaning; `title` heads it.
  template <class T>
  std::string default_scene_text(std::string_view title)
  {
    std::ostringstream out;
    out << "# " << title << "\n"
        << "# Every key with its default. Quantities are strings with units (\"2500 kN/mm\", "
           "\"15 cm\", \"5 %\");\n"
        << "# any unit of the same dimension is accepted. Keys left out keep these defaults.\n";
    T               defaults;
    DefaultsPrinter printer(out);
    visit(printer, defaults);
    return out.str();
  }

  /// JSON schema of T (see SchemaWriter): every key with type, unit, default, range and doc.
  template <class T>
  std::string schema_text()
  {
    T            defaults;
    SchemaWriter writer;
    visit(writer, defaults);
    return writer.dump(2) + "\n";
  }

  // Scene structs give every member a default initializer (docs/architecture.md "Scenes and
  // errors"), so they are default-initialized (`T scene;`): value-initialization `T{}` of such
  // aggregates trips a false -Wmaybe-uninitialized of GCC 12 at -O3.

  /**
   * Parse, visit, then validate (free `validate(const T&, ValidationContext&)` found by ADL, or a
   * member `validate(ValidationContext&) const`). `name` is used in error messages. Paths in
   * the scene are relative to `directory` (the scene file's directory): validate() sees them as
   * written (ValidationContext::directory() resolves them), then a free
   * `resolve_paths(T&, const std::filesystem::path&)`, if T has one, rewrites them resolved, so
   * that the scene returned (and its resolved JSON) works from any working directory.
   * @throws SceneError naming file, line, key path, value and expectation.
   */
  template <class T>
  LoadedScene<T>
  read_scene_text(std::string text, std::string name, const std::filesystem::path &directory = {})
  {
    SceneSource source(name);
    T           scene;
    SceneReader reader = SceneReader::root(text, source);
    visit(reader, scene);
    reader.finish();

    ValidationContext context = source.read_failures();
    context.set_directory(directory);
    if constexpr (detail::HasMemberValidate<T>::value)
      scene.validate(context);
    else if constexpr (detail::HasFreeValidate<T>::value)
      validate(static_cast<const T &>(scene), context);
    source.throw_if_failed(context);
    if constexpr (detail::HasResolvePaths<T>::value)
      resolve_paths(scene, directory);

    std::string resolved = to_json_text(scene);
    return {std::move(scene), std::move(name), std::move(text), std::move(resolved)};
  }

  /// read_scene_text() of a file.
  template <class T>
  LoadedScene<T> read_scene(const std::filesystem::path &file)
  {
    return read_scene_text<T>(detail::read_text_file(file), file.string(), file.parent_path());
  }

  /// The validated scene of `file` (see read_scene_text()).
  template <class T>
  T load_scene(const std::filesystem::path &file)
  {
    return read_scene<T>(file).scene;
  }

  /// The validated scene of `text`, named `name` in messages (see read_scene_text()).
  template <class T>
  T load_scene_text(std::string text, std::string name, const std::filesystem::path &directory = {})
  {
    return read_scene_text<T>(std::move(text), std::move(name), directory).scene;
  }
} // namespace kimp::io
