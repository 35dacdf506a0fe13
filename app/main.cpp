// unsatmpm: the command-line program (app/command_line.hpp).
#include "app/command_line.hpp"

int main(int argc, char** argv) { return unsatmpm::run_command_line(argc, argv); }
