// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
#include <exception>
#include <iostream>

#include "pipeline/cli.h"

int main(int argc, char **argv)
{
  try
  {
    const auto app = kimp::pipeline::make_app();
    // Engines add their commands here as they land (register_<name>_command in cli.h).
    return kimp::pipeline::run_app(*app, argc, argv, std::cout, std::cerr);
  }
  catch (const std::exception &error)
  {
    std::cerr << "error: " << error.what() << '\n';
    return 1;
  }
}
