// `kimp` global options and argument handling; see cli.h.
#include "cli/cli.h"

#include <ostream>

#include "base/version.h"

namespace kimp::cli
{
  using namespace kimp::base;
  using namespace kimp::io;
  std::unique_ptr<CLI::App> make_app()
  {
    auto app = std::make_unique<CLI::App>(
      "kimp: impact stiffness of moat walls and pounding analyses of seismically isolated "
      "buildings",
      "kimp");
    app->set_version_flag("--version", version_line());
    app->fallthrough();

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
      err << "error: " << error.what() << "\nRun '" << app.get_name()
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
