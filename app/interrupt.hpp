// SIGINT and SIGTERM end a run cleanly: the handler only records the signal, and the run loop
// (app/run_loop.hpp) checks it after every step, writes the state reached as an output frame, a
// summary with status "interrupted", and exits with 128 + the signal's number (docs/output.md).
// A second signal while the run is writing is ignored; kill -9 cannot be caught (the next run
// reports the stale lock instead, writers/output_folder.hpp).
#pragma once

namespace unsatmpm {

/// Installs the handlers of SIGINT and SIGTERM (idempotent).
void install_interrupt_handlers();
/// The signal received since the handlers were installed, or 0.
int interrupt_signal();
/// How many signals were received since the handlers were installed.
int interrupt_count();
/// "SIGINT", "SIGTERM" or "signal N".
const char* signal_name(int signal);

}  // namespace unsatmpm
