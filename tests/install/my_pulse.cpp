// my_pulse: the source of problems/gaussian_pulse (included, not copied),
// built out of tree against an installed mote by the test install.find_package
// (tests/install/install_and_use.py), as a user's own problem would be. Only
// the executable's name differs; it reports itself as gaussian_pulse.
#include "../../problems/gaussian_pulse/gaussian_pulse.cpp"  // NOLINT(bugprone-suspicious-include)
