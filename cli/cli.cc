// `kimp` global options and argument handling; see cli.h.
#include "cli/cli.h"

#include <algorithm>
#include <cctype>
#include <ostream>
#include <string_view>

#include "base/format.h"
#include "base/version.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;

  namespace
  {
    /// "unknown command 'lumpd'; did you mean 'lumped'?" when the first word that is not an
    /// option names no command; "" otherwise.
    std::string unknown_command(const CLI::App &app, int argc, const char *const *argv)
    {
      for (int i = 1; i < argc; ++i)
      {
        const std::string word = argv[i];
        if (word.empty() || word[0] == '-')
          continue;
        std::string suggestion;
        std::size_t best = 3; // more than two edits away is not a typo
        std::string known;
        for (const CLI::App *command : app.get_subcommands({}))
        {
          if (command->get_name() == word)
            return "";
          known += (known.empty() ? "" : ", ") + command->get_name();
          if (const std::size_t d = io::edit_distance(word, command->get_name()); d < best)
          {
            best       = d;
            suggestion = command->get_name();
          }
        }
        return "unknown command '" + word + "'" +
               (suggestion.empty() ? std::string() : "; did you mean '" + suggestion + "'?") +
               " (commands: " + known + ")";
      }
      return "";
    }
  } // namespace

  std::unique_ptr<CLI::App> make_app()
  {
    auto app = std::make_unique<CLI::App>(
      "kimp: impact stiffness of moat walls and pounding analyses of seismically isolated "
      "buildings",
      "kimp");
    app->set_version_flag("--version", version_line());
    app->fallthrough();
    // One command per call: a positional that names a command ("kimp export-opensees study", the
    // default output directory of `kimp study`) is then the argument, not a second command.
    app->require_subcommand(0, 1);

    // Read the flag counts (reset by every parse), not bound variables (kept between parses).
    CLI::Option *verbose = app->add_flag("-v,--verbose", "more log output (-vv: everything)");
    CLI::Option *quiet =
      app->add_flag("-q,--quiet", "warnings and errors only, no progress line")->excludes(verbose);
    app->parse_complete_callback(
      [verbose, quiet]()
      {
        if (quiet->count() > 0)
          set_verbosity(Verbosity::quiet);
        else if (verbose->count() >= 2)
          set_verbosity(Verbosity::trace);
        else if (verbose->count() == 1)
          set_verbosity(Verbosity::verbose);
        else
          set_verbosity(Verbosity::normal);
      });
    return app;
  }

  int run_app(CLI::App          &app,
              int                argc,
              const char *const *argv,
              std::ostream      &out,
              std::ostream      &err)
  {
    try
    {
      app.parse(argc, argv);
    }
    catch (const PrintDefaults &listing)
    {
      out << listing.text();
      return 0;
    }
    catch (const CLI::ParseError &error)
    {
      if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
        return app.exit(error, out, err);
      if (app.get_subcommands().empty())
        if (const std::string unknown = unknown_command(app, argc, argv); !unknown.empty())
        {
          err << "error: " << base::shorten_long_words(unknown) << "\nRun '" << app.get_name()
              << " --help' for more information.\n";
          return 2;
        }
      // CLI11 quotes a bad argument whole: at most base::quoted_value_limit characters of it.
      err << "error: " << base::shorten_long_words(error.what()) << "\nRun '" << app.get_name()
          << " --help' for more information.\n";
      return 2;
    }
    if (app.get_subcommands().empty())
    {
      err << "error: no command given\n" << app.help();
      return 2;
    }
    return 0;
  }

  int run_app(CLI::App                       &app,
              const std::vector<std::string> &arguments,
              std::ostream                   &out,
              std::ostream                   &err)
  {
    std::vector<const char *> argv{app.get_name().c_str()};
    for (const auto &a : arguments)
      argv.push_back(a.c_str());
    return run_app(app, static_cast<int>(argv.size()), argv.data(), out, err);
  }
} // namespace kimp::cli
