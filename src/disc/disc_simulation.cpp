// The coupled dust-gas disc simulation (RBO24 sec. 3 and 6); see
// include/mote/disc/disc_simulation.hpp.
#include "mote/disc/disc_simulation.hpp"

#include <climits>
#include <limits>
#include <string>
#include <utility>

#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/mesh/boundaries.hpp"
#include "mote/mesh/grid_output.hpp"

namespace mote::disc {

namespace {

/// Kernel of well_mixed, in a named function (CUDA extended lambdas cannot sit in a lambda).
void fill_well_mixed(const mesh::Grid& grid, const GasFields& gas, const View<Real****>& W, const RealView1& ratio,
                     Real floor, Real gas_floor) {
  auto rho = gas.rho, vR = gas.vR, vphi = gas.vphi, vZ = gas.vZ;
  par_for(
      "disc::well_mixed_dust", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(), 0,
      static_cast<int>(W.extent(2)), KOKKOS_LAMBDA(int i, int j, int s) {
        W(i, j, s, kRho) = rho(i, j) > gas_floor ? math::max(ratio(s) * rho(i, j), floor) : floor;
        W(i, j, s, kVR) = vR(i, j);
        W(i, j, s, kVphi) = vphi(i, j);
        W(i, j, s, kVZ) = vZ(i, j);
      });
}

}  // namespace

DiscSimulation::InitialDust DiscSimulation::well_mixed(std::vector<double> dust_to_gas, double floor,
                                                       double gas_floor) {
  return [eps = std::move(dust_to_gas), floor, gas_floor](const mesh::Grid& grid, const GasFields& gas,
                                                          const View<Real****>& W) {
    const int ns = static_cast<int>(W.extent(2));
    if (static_cast<int>(eps.size()) != ns)
      throw core::DeckError(logging::cat("well-mixed dust: ", eps.size(), " dust-to-gas ratios for ", ns, " species"));
    RealView1 ratio("disc::dust_to_gas", ns);
    auto ratio_h = Kokkos::create_mirror_view(ratio);
    for (int s = 0; s < ns; ++s) ratio_h(s) = eps[s];
    Kokkos::deep_copy(ratio, ratio_h);
    fill_well_mixed(grid, gas, W, ratio, floor, gas_floor);
  };
}

namespace {

/// On the disc the collisions' k_B T = mu m_H c_s^2 (RBO24 eq. 58) takes c_s
/// from the gas, whose c_s^2 = k_B T / (mu m_H) uses gas.mu: a different
/// coagulation.mu would give them another temperature (2.6 % apart with the
/// two defaults, 2.34 and 2.4). The disc therefore uses gas.mu, and a
/// coagulation.mu given in the deck must agree with it.
void check_coagulation_mu(const core::Deck& d, core::DeckCheck& check) {
  if (!d.has_table("coagulation") || d.where("coagulation.mu").find("(default)") != std::string::npos) return;
  if (d.real("coagulation.mu") != d.real("gas.mu"))
    check.fail("coagulation.mu", "must equal " + check.quote("gas.mu") +
                                     ": the disc's coagulation takes the gas's mean molecular weight; set gas.mu");
}

}  // namespace

void DiscSimulation::declare(core::DeckSchema& schema) {
  mesh::GridSpec::declare(schema);
  mesh::Boundaries::declare(schema);
  GasDisc::declare(schema);
  DustSettings::declare(schema);
  DriverSettings::declare(schema);
  coagulation::declare(schema);
  radiation::declare(schema);
  TemperatureSettings::declare(schema);
  schema.rule(check_coagulation_mu);
}

DiscSimulation::DiscSimulation(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units,
                               const InitialDust& initial_dust)
    : units_(units),
      grid_(std::make_unique<mesh::Grid>(mesh::GridSpec::from_deck(deck), comm)),
      gas_(std::make_unique<GasDisc>(deck, *grid_, units)) {
  auto dust_settings = DustSettings::from_deck(deck, units, gas_->config().gravity());
  dust_settings.gas_floor = gas_->config().rho_floor;
  dust_ = std::make_unique<DustDynamics>(*grid_, std::move(dust_settings));
  dust_->set_gas(gas_->fields());
  initial_dust(*grid_, gas_->fields(), dust_->W);
  dust_->initialise_from_primitives();
  driver_ = std::make_unique<DiscDriver>(*dust_, *gas_, DriverSettings::from_deck(deck));
  if (deck.has_table("radiation")) {
    // RBO24 sec. 6: the temperature on its own adaptive schedule, before coagulation (which reads c_s).
    temperature_ = std::make_unique<DiscTemperature>(*grid_, *gas_, *dust_, radiation::from_deck(deck, units),
                                                     TemperatureSettings::from_deck(deck), units);
    driver_->add({"temperature", Schedule::adaptive(),
                  [this](double, double elapsed) { temperature_->update(elapsed); },
                  [this] { return temperature_->next_interval(); }});
  }
  if (deck.has_table("coagulation")) {
    // RBO24 sec. 6: coagulation on its own adaptive schedule, after the dust step.
    auto coag_settings = coagulation::settings_from_deck(deck);
    coag_settings.mu = gas_->config().mu;  // the gas's c_s^2 = k_B T / (mu m_H) (check_coagulation_mu)
    coag_ = std::make_unique<DiscCoagulation>(*grid_, *dust_, std::move(coag_settings), units);
    driver_->add({"coagulation", Schedule::adaptive(DriverSettings::from_deck(deck).coagulation_max_interval),
                  [this](double, double elapsed) { coag_->update(gas_->fields(), elapsed); },
                  [this] { return coag_->next_interval(); }});
  }
}

void DiscSimulation::write_snapshot(io::SnapshotWriter& out) const {
  mesh::describe_grid(out, *grid_);
  gas_->write_snapshot(out);
  const auto& u = units_;
  // One host copy of the dust state and the stopping times per snapshot, every species' fields taken from it.
  const auto W = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust_->W);
  const auto ts = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dust_->stopping_times());
  const int ns = dust_->species();
  auto field = [&](const auto& h, auto... trailing) { return mesh::active_cells_of_host(*grid_, h, trailing...); };
  for (int s = 0; s < ns; ++s) {
    const std::string n = std::to_string(s);
    out.cell_field("dust_rho_" + n, field(W, s, kRho).data(), {"code density", u.density()});
    out.cell_field("dust_vR_" + n, field(W, s, kVR).data(), {"code velocity", u.velocity()});
    out.cell_field("dust_vphi_" + n, field(W, s, kVphi).data(), {"code velocity", u.velocity()});
    out.cell_field("dust_vZ_" + n, field(W, s, kVZ).data(), {"code velocity", u.velocity()});
    out.cell_field("dust_ts_" + n, field(ts, s).data(), {"code time", u.time});
  }
  RealView2 vK("disc::v_kepler", grid_->nr_total(), grid_->nt_total());
  auto Rc = grid_->Rc;
  auto Zc = grid_->Zc;
  const StellarGravity star = gas_->config().gravity();
  par_for(
      "disc::v_kepler", 0, grid_->nr_total(), 0, grid_->nt_total(), KOKKOS_LAMBDA(int i, int j) {
        Real gR, gZ;
        star.acceleration(Rc(i), Zc(i, j), gR, gZ);
        vK(i, j) = math::sqrt(math::max(-Rc(i) * gR, Real(0)));
      });
  out.cell_field("v_K", mesh::active_cells(*grid_, vK).data(), {"code velocity", u.velocity()});
  std::vector<double> sizes_cm;
  for (double a : dust_->settings().sizes) sizes_cm.push_back(a * u.length);
  out.array("dust_sizes", io::Block::whole({hsize_t(ns)}), sizes_cm.data(), {"cm", 1.0});
  const double gm = star.GM;
  out.array("GM", io::Block::whole({1}), &gm,
            {"code length^3 / code time^2", u.length * u.length * u.length / (u.time * u.time)});
  if (temperature_) temperature_->write_snapshot(out);
}

void DiscSimulation::save_state(io::H5File& file) const {
  mesh::write_state(file, "/state/dust_Q", *grid_, dust_->Q);
  mesh::write_state(file, "/state/dust_W", *grid_, dust_->W);
  mesh::write_state(file, "/state/dust_budget", *grid_, dust_->budget);
  gas_->save_state(file);
  driver_->save_state(file);
  if (temperature_) temperature_->save_state(file);
  if (coag_) coag_->save_state(file);
}

void DiscSimulation::load_state(const io::H5File& file) {
  mesh::read_state(file, "/state/dust_Q", *grid_, dust_->Q);
  mesh::read_state(file, "/state/dust_W", *grid_, dust_->W);
  if (file.exists("/state/dust_budget"))  // checkpoints before the budget: it restarts from zero
    mesh::read_state(file, "/state/dust_budget", *grid_, dust_->budget);
  if (temperature_) temperature_->load_state(file);  // hands T to the gas before its structure is rebuilt
  gas_->load_state(file);
  dust_->set_gas(gas_->fields());
  driver_->load_state(file);
  if (coag_) coag_->load_state(file);
}

std::string DiscSimulation::work_summary() const {
  const std::string schedule = driver_->schedule_summary();
  return temperature_ ? schedule + "\n" + temperature_->solve_summary() : schedule;
}

double DiscSimulation::min_dust_density() const {
  auto Q = dust_->Q;
  const int ns = dust_->species();
  Real m = std::numeric_limits<Real>::max();
  par_reduce(
      "disc::dust_rho_min", grid_->i_begin(), grid_->i_end(), grid_->j_begin(), grid_->j_end(),
      KOKKOS_LAMBDA(int i, int j, Real& acc) {
        for (int s = 0; s < ns; ++s) acc = math::min(acc, Q(i, j, s, kRho));
      },
      Kokkos::Min<Real>(m));
  return grid_->comm().min(m);
}

std::string DiscSimulation::dt_limit() const {
  const DustDynamics::StepLimit limit = dust_->step_limit();
  std::string out = std::string("dust ") + DustDynamics::StepLimit::describe(limit.kind);
  if (limit.kind == DustDynamics::StepLimit::kNone) return out;
  const int s = limit.species;
  return out + logging::format(" of species %d (a = %.3g cm) at R = %.4g au, theta = %.4g (cell %d, %d)", s,
                               dust_->settings().sizes[static_cast<size_t>(s)] * units_.length,
                               limit.R * units_.length / units::cgs::au, limit.theta, limit.i, limit.j);
}

std::vector<io::Diagnostic> DiscSimulation::diagnostics() const {
  std::vector<io::Diagnostic> d;
  double total = 0.0;
  const auto masses = dust_->species_masses();
  for (size_t s = 0; s < masses.size(); ++s) {
    d.push_back({"dust_mass_" + std::to_string(s), masses[s]});
    total += masses[s];
  }
  const auto budget = dust_->mass_budget();
  d.push_back({"dust_mass", total});
  d.push_back({"dust_floor_added", budget.floor_added});
  d.push_back({"dust_outflow", budget.outflow});
  d.push_back({"dust_rho_min", min_dust_density()});
  d.push_back({"gas_mass", gas_->mass()});
  for (const auto& t : driver_->diagnostics()) d.push_back(t);
  if (temperature_)
    for (const auto& t : temperature_->diagnostics()) d.push_back(t);
  return d;
}

std::optional<io::NonFinite> DiscSimulation::find_non_finite() const {
  // The dust's Q first, then the gas fields in their order: one reduction over
  // field * cells + cell, one host synchronisation per check.
  auto Q = dust_->Q;
  const GasFields g = gas_->fields();
  const int ib = grid_->i_begin(), jb = grid_->j_begin(), nt = grid_->nt, ns = dust_->species();
  const int cells = grid_->nr * grid_->nt;
  int first = INT_MAX;
  par_reduce(
      "disc::non_finite", ib, grid_->i_end(), jb, grid_->j_end(),
      KOKKOS_LAMBDA(int i, int j, int& f) {
        bool dust_ok = true;
        for (int s = 0; s < ns; ++s)
          for (int k = 0; k < kDustVars; ++k) dust_ok = dust_ok && math::isfinite(Q(i, j, s, k));
        const int field = dust_ok ? 1 + first_failing_gas_field(g, i, j) : 0;
        if (field != 1 + kGasCheckFields) f = math::min(f, field * cells + (i - ib) * nt + (j - jb));
      },
      Kokkos::Min<int>(first));
  if (first == INT_MAX) return std::nullopt;
  const int field = first / cells, cell = first % cells;
  if (field > 0) return gas_->describe_non_finite(field - 1, cell);
  const int i = cell / nt, j = cell % nt;
  return io::NonFinite{"dust Q", logging::format("cell (i, j) = (%d, %d), R = %g, theta = %g", i + grid_->i_offset, j,
                                                 grid_->Rc_h(i + ib), grid_->tc_h(j + jb))};
}

}  // namespace mote::disc
