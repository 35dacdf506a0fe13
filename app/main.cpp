// unsatmpm: the command-line program (app/command_line.hpp).
#include <csignal>

#include "app/command_line.hpp"

int main(int argc, char** argv) {
  // A reader of the program's output that has gone (`| head`, a closed pipe or terminal) must not
  // end a run: by default the next write raises SIGPIPE, which killed the run at once, without
  // its summary or checkpoint (a run piped through `head -c 20` died with exit 141 before its
  // output folder existed). Ignored, the write fails and the run goes on.
  std::signal(SIGPIPE, SIG_IGN);
  return unsatmpm::run_command_line(argc, argv);
}
