// The shared prologue of the SPH problem executables; see include/mote/setups/sph_problem.hpp.
#include "mote/setups/sph_problem.hpp"

#include "mote/core/deck.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/io/run_loop.hpp"
#include "mote/sph/sph_settings.hpp"

namespace mote::sph {

void declare_sph_problem(core::DeckSchema& schema, const std::string& problem, const SphProblemDeclaration& what) {
  declare_settings(schema);
  io::RunSettings::declare_sph_format(schema);
  if (!what.eos.empty()) schema.rule(io::requires_choice(problem, "sph.eos", what.eos));
  if (what.dust_methods.empty()) return;
  DustSettings::declare(schema);
  if (what.dust_required) schema.rule(io::requires_table(problem, "dust"));
  schema.rule(requires_dust_method(problem, what.dust_methods));
}

SphProblemStart start_sph_problem(const io::ProblemContext& ctx, const std::string& problem, int dim) {
  if (ctx.comm.size() > 1)
    throw core::DeckError(problem + ": the SPH engine runs on one MPI rank (no particle decomposition yet)");
  SphProblemStart start;
  start.cfg = config_from_deck(ctx.deck, dim);
  if (ctx.deck.has_table("dust")) start.dust = DustSettings::from_deck(ctx.deck);
  return start;
}

}  // namespace mote::sph
