// Exit codes of the executables (see include/mote/core/exit_codes.hpp).
#include "mote/core/exit_codes.hpp"

namespace mote::core {

ExitCode exit_code_of(const std::exception& error) {
  if (dynamic_cast<const InputError*>(&error)) return kExitBadInput;
  if (dynamic_cast<const NumericalError*>(&error)) return kExitNonFinite;
  if (dynamic_cast<const IOError*>(&error)) return kExitIOError;
  return kExitError;
}

}  // namespace mote::core
