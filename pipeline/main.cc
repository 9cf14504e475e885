// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
#include <iostream>

#include "pipeline/version.h"

int main()
{
  std::cout << "kimp " << kimp::version << " (" << kimp::git_revision << ")\n";
  return 0;
}
