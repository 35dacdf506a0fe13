// unsatmpm's command line: the subcommands run, resume, check and bench, their options, and the
// exit codes (app/command_line.cpp). In the app library, so that its compile (CLI11 is heavy)
// runs beside the others instead of after them (CMakeLists.txt, CMAKE_OPTIMIZE_DEPENDENCIES).
#pragma once

namespace unsatmpm {

/// Parses argv and runs the subcommand; returns the process's exit code.
int run_command_line(int argc, char** argv);

}  // namespace unsatmpm
