// The exit codes of every mote executable (the table in docs/quickstart.md)
// and the exception types that carry a failure up to run_problem, the one
// place that turns it into an exit code: bad input, a numerical failure or an
// I/O error ends every problem, grid or SPH, with the same code.
#pragma once

#include <exception>
#include <stdexcept>

namespace mote::core {

enum ExitCode : int {
  kExitFinished = 0,     // reached run.t_end
  kExitStepLimit = 0,    // stopped at run.max_steps after writing a checkpoint
  kExitError = 1,        // an unexpected failure (a bug): report it
  kExitBadInput = 2,     // deck, command line or a checkpoint to restart from rejected
  kExitNonFinite = 3,    // NaN/Inf in a field, a time-step below run.dt_min, a solver that failed
  kExitInterrupted = 4,  // stopped by SIGINT/SIGTERM after writing a checkpoint
  kExitIOError = 5,      // a file or directory could not be written or read
};

/// Input that cannot be run: a deck, a command line or a checkpoint (exit 2).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A state the solvers cannot continue from: a non-finite value, a time-step
/// below run.dt_min, an iteration that did not converge (exit 3).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file or directory that could not be created, written or read (exit 5).
class IOError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The I/O error of another rank, which reports it: this rank stops with the same exit code (5)
/// without repeating the message.
class PeerIOError : public IOError {
 public:
  using IOError::IOError;
};

/// The exit code of a run ended by `error`.
ExitCode exit_code_of(const std::exception& error);

}  // namespace mote::core
