#include "app/helper_programs.h"

#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>

#include "base/logging.h"

extern char **environ;

namespace kimp::app
{
  std::filesystem::path find_helper_script(const std::string &file_name)
  {
    std::vector<std::filesystem::path> candidates;
    if (const char *data_dir = std::getenv("KIMP_DATA_DIR"); data_dir != nullptr && *data_dir)
    {
      candidates.push_back(std::filesystem::path(data_dir) / "scripts");
      candidates.push_back(std::filesystem::path(data_dir) / ".." / "scripts");
    }
    // The source tree kimp was built from (a compile definition of kimp::app).
    candidates.push_back(std::filesystem::path(KIMP_SOURCE_TREE) / "scripts");
    for (const auto &directory : candidates)
    {
      const std::filesystem::path script = directory / file_name;
      std::error_code             error;
      if (std::filesystem::is_regular_file(script, error))
        return script.lexically_normal();
    }
    return {};
  }

  int run_program(const std::vector<std::string> &arguments,
                  ProgramOutput                   output,
                  const std::filesystem::path    &log)
  {
    if (arguments.empty())
      return -1;
    std::vector<char *> argv;
    for (const auto &a : arguments)
      argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (output == ProgramOutput::errors)
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    else if (output == ProgramOutput::discard)
    {
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
      posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    }
    else if (output == ProgramOutput::append)
    {
      posix_spawn_file_actions_addopen(&actions,
                                       STDOUT_FILENO,
                                       log.c_str(),
                                       O_WRONLY | O_CREAT | O_APPEND,
                                       0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    pid_t     pid    = 0;
    const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (failed != 0)
      return -1;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
      return -1;
    return WEXITSTATUS(status);
  }

  ChartScriptRun run_chart_script(const std::string           &script_name,
                                  const std::filesystem::path &output_dir)
  {
    ChartScriptRun run;
    run.script = find_helper_script(script_name);
    if (run.script.empty())
      return run;
    run.log = output_dir / "charts" / "charts.log";
    std::filesystem::create_directories(run.log.parent_path());
    std::filesystem::remove(run.log);
    run.status = run_program({"/usr/bin/python3", run.script.string(), output_dir.string()},
                             ProgramOutput::append,
                             run.log);
    return run;
  }

  bool draw_optional_charts(const std::string           &script_name,
                            const std::filesystem::path &output_dir,
                            const std::string_view       what)
  {
    const ChartScriptRun run = run_chart_script(script_name, output_dir);
    if (run.script.empty())
      base::logger().warn("{} skipped: scripts/{} not found (set KIMP_DATA_DIR to the kimp source "
                          "tree)",
                          what,
                          script_name);
    else if (run.status != 0)
      base::logger().warn("{} skipped: {} exited with {} (needs /usr/bin/python3 with matplotlib "
                          "and h5py; Debian python3-matplotlib python3-h5py); see {}",
                          what,
                          run.script.string(),
                          run.status,
                          run.log.string());
    return !run.script.empty() && run.status == 0;
  }
} // namespace kimp::app
