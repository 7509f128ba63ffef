// Ctrl-C (SIGINT) and SIGTERM. main() installs the handlers for every command: by default a
// signal removes the temporaries of the writes in progress (io/atomic_file.h) and ends the
// process at once with exit code 128 + the signal, so an interrupted command leaves only whole
// files. A command with a frame loop calls allow_graceful_stop(): then the first signal only
// raises stop_flag() (the loop finishes the frame it is in, writes it whole and ends), and a
// second one aborts at once as above. SIGXFSZ is ignored so that a file size limit makes a
// write fail with an error message instead of killing the process.
#pragma once

#include <atomic>

namespace ddish::app {

// Signals whose disposition was "ignore" when ddish started (a background job of a script)
// are left ignored.
void install_interrupt_handlers();

// From now on the first SIGINT / SIGTERM asks for a stop instead of aborting.
void allow_graceful_stop();

// Raised by the first signal after allow_graceful_stop().
const std::atomic<bool>& stop_flag();

// The signal that raised stop_flag(), 0 if none.
int stop_signal();

// The conventional exit code of a run ended by `signal`: 128 + signal.
inline int interrupted_exit_code(int signal) { return 128 + signal; }

}  // namespace ddish::app
