// my_dustybox: the source of problems/sph_dustybox (included, not copied),
// built out of tree against an installed mote and linked to the installed
// mote::setups (its lattice, SPH prologue and dustybox set-up) by the test
// install.find_package (tests/install/install_and_use.py), as a user's own SPH
// problem would be. It reports itself as sph_dustybox.
#include "../../problems/sph_dustybox/sph_dustybox.cpp"  // NOLINT(bugprone-suspicious-include)
