// What every catalog effect must do, generated from EffectCatalog::builtin(): a new effect is
// held to these without being named here. Its declarations agree with each other (realistic,
// plausible, fit and allowed ranges), its neutral values leave a simulated measurement unchanged
// bit for bit, and the stage and channels it declares are the ones it changes. Its own physics
// is tested in tests/cpp/effects/<name>.test.cpp.

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "effect_test_support.hpp"
#include "pamkit/muscle/free_inflation.hpp"

namespace {

using namespace pamkit_test;

// Every built-in effect at its defaults, and once per channel for those that take one.
std::vector<EffectPtr> every_effect() {
  std::vector<EffectPtr> out;
  const EffectCatalog catalog = EffectCatalog::builtin();
  for (const std::string& name : catalog.names()) {
    if (catalog.make(name)->options().count("channel") == 0) {
      out.push_back(catalog.make(name));
      continue;
    }
    for (const std::string& channel : measured_channels()) {
      out.push_back(catalog.make(name));
      out.back()->set("channel", channel);
    }
  }
  return out;
}

std::string label(const Effect& e) {
  std::ostringstream text;
  text << e.name();
  for (const auto& [key, value] : e.options()) text << " " << key << "=" << value;
  return text.str();
}

// Sets every parameter that declares a neutral value to it; false if none does.
bool make_neutral(Effect& e) {
  bool any = false;
  for (const EffectParameter& p : e.parameters()) {
    if (std::isnan(p.neutral)) continue;
    e.set_value(p.name, p.neutral);
    any = true;
  }
  return any;
}

// The sealed bench: table C.2's 90 % test, two cycles with holds, so that every stage has
// something to act on.
ElongationTrajectory sealed_bench() { return thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0); }

// The supplied bench: PAM 2 held at its free length at 150 kPa while the regulator raises the
// pressure from 20 to 300 kPa and lowers it again, so that below 150 kPa the thesis's braid
// pushes and the two branches of the sweep are both there.
struct SuppliedBench {
  double length_m;
  ElongationTrajectory crosshead;
  std::vector<double> gauge_pressure_Pa;
};
SuppliedBench supplied_bench() {
  const MuscleParams params;
  const double length =
      free_inflation(BraidGeometry(params.build), params.bladder, params.gas.atmospheric_pressure_Pa, 150e3).length_m;
  std::vector<double> time, pressure;
  for (int k = 0; k <= 56; ++k) {
    time.push_back(0.5 * k);
    pressure.push_back(k <= 28 ? 20e3 + 10e3 * k : 300e3 - 10e3 * (k - 28));
  }
  return {length, ElongationTrajectory(time, std::vector<double>(time.size(), 0.0)), pressure};
}

Measurement run(GasMode mode, const MuscleParams& params, const std::vector<EffectPtr>& effects) {
  if (mode == GasMode::sealed) {
    return simulate_measurement(params, table_c2_90(), sealed_bench(), effects, precise_simulator());
  }
  const SuppliedBench bench = supplied_bench();
  return simulate_supplied_measurement(params, bench.length_m, bench.crosshead, bench.gauge_pressure_Pa, effects);
}

// The mode an effect is checked in: the sealed bench where it acts there, else the supplied one.
GasMode home(const Effect& e) { return e.acts_in(GasMode::sealed, nullptr) ? GasMode::sealed : GasMode::supplied; }

// The thesis's model with heat exchange at a finite rate, so that the gas temperature swings
// and a lag or a skew of temperature_K shows (the default gas is isothermal).
MuscleParams swinging_temperature() {
  MuscleParams params;
  params.gas.process = GasProcess::heat_transfer;
  params.gas.heat_transfer_time_constant_s = 2.0;
  return params;
}

}  // namespace

TEST_CASE("every effect: a name, a description, a signature, and acts in a test of some kind",
          "[effects][catalog][every_effect]") {
  const EffectCatalog catalog = EffectCatalog::builtin();
  for (const std::string& name : catalog.names()) {
    const EffectPtr e = catalog.make(name);
    INFO(name);
    CHECK(e->name() == name);
    CHECK_FALSE(e->description().empty());
    // what the effect is, then what gives it away: the two columns of the documentation's table
    const std::size_t away = e->description().find("Gives it away: ");
    CHECK(away != std::string::npos);
    CHECK(away > 0);
    CHECK_FALSE(e->signature().empty());
    CHECK((e->acts_in(GasMode::sealed, nullptr) || e->acts_in(GasMode::supplied, nullptr)));
    for (const GasMode mode : {GasMode::sealed, GasMode::supplied}) {
      std::string why;
      if (e->acts_in(mode, &why)) continue;
      CHECK(why.find(name) != std::string::npos);  // the reason names the effect
    }
  }
}

// What an effect declares beside its allowed range is read by synthetic data (realistic), the
// diagnosis's search (fit) and its decision (plausible); these are the orderings that make the
// three agree: synthetic data never draws an implausible value, every plausible value is allowed
// and can be reached by a fit, and a fit that ends at its bound is outside the plausible interior.
TEST_CASE("every effect: realistic inside plausible inside allowed, plausible reachable by the fit, fit inside allowed",
          "[effects][catalog][every_effect]") {
  for (const std::string& name : EffectCatalog::builtin().names()) {
    const EffectPtr e = EffectCatalog::builtin().make(name);
    for (const EffectParameter& p : e->parameters()) {
      INFO(name << "." << p.name);
      CHECK_FALSE(p.unit.empty());
      CHECK_FALSE(p.plausible_source.empty());
      CHECK(p.min <= p.value);
      CHECK(p.value <= p.max);
      const double realistic_low = p.either_sign ? -p.realistic_max : p.realistic_min;
      CHECK(p.realistic_min <= p.realistic_max);
      CHECK(p.plausible_min <= realistic_low);
      CHECK(p.realistic_max <= p.plausible_max);
      CHECK(p.min <= p.plausible_min);
      CHECK(p.plausible_max <= p.max);
      CHECK(p.min <= p.fit_min);
      CHECK(p.fit_max <= p.max);
      if (!std::isnan(p.neutral)) {
        CHECK(p.min <= p.neutral);
        CHECK(p.neutral <= p.max);
      }
      if (p.fit_min == p.fit_max) {  // held, not searched: at the effect's default
        CHECK(p.fit_start == p.fit_min);
        CHECK(p.value == p.fit_start);
        continue;
      }
      CHECK(p.fit_min < p.fit_start);
      CHECK(p.fit_start < p.fit_max);
      CHECK(p.plausible_max <= p.fit_max);  // plausible values are reachable: the bound lies beyond
      if (p.fit_scale != FitScale::linear) CHECK(p.fit_min > 0.0);  // log and reciprocal need a positive end
    }
  }
}

TEST_CASE("every effect: a number set as a number equals the same number set as text",
          "[effects][catalog][every_effect]") {
  const auto value_of = [](const Effect& e, const std::string& key) {
    for (const EffectParameter& p : e.parameters()) {
      if (p.name == key) return p.value;
    }
    FAIL("effect " << e.name() << " has no parameter " << key);
    return 0.0;
  };
  for (const std::string& name : EffectCatalog::builtin().names()) {
    for (const EffectParameter& p : EffectCatalog::builtin().make(name)->parameters()) {
      // A value with no short decimal form, inside every allowed range.
      const double value = p.fit_start != 0.0 ? p.fit_start * 4.0 / 3.0 : 1.0 / 7.0;
      const EffectPtr typed = EffectCatalog::builtin().make(name);
      const EffectPtr text = EffectCatalog::builtin().make(name);
      typed->set_value(p.name, value);
      std::ostringstream printed;
      printed.precision(17);
      printed << value;
      text->set(p.name, printed.str());
      INFO(name << "." << p.name);
      CHECK(value_of(*typed, p.name) == value_of(*text, p.name));
    }
  }
}

TEST_CASE("every effect: at its neutral values it leaves the default model's measurement unchanged, bit for bit",
          "[effects][catalog][every_effect]") {
  // The baseline is the thesis's model with its default, isothermal gas (n = 1): heat exchange
  // with tau = 0 is instantaneous, i.e. isothermal, and so neutral.
  for (const GasMode mode : {GasMode::sealed, GasMode::supplied}) {
    const Measurement baseline = run(mode, MuscleParams(), {});
    std::vector<EffectPtr> all_neutral;
    for (const EffectPtr& e : every_effect()) {
      if (!e->acts_in(mode, nullptr)) continue;
      // An effect with no neutral value (braid_slack: no band width is "no slack") is held to
      // its own file's tests of where it leaves the force alone.
      if (!make_neutral(*e)) continue;
      INFO(label(*e) << (mode == GasMode::sealed ? ", sealed" : ", supplied"));
      CHECK(identical(run(mode, MuscleParams(), {e}), baseline));
      all_neutral.push_back(e);
    }
    INFO((mode == GasMode::sealed ? "sealed" : "supplied") << ": " << all_neutral.size() << " neutral effects at once");
    CHECK(all_neutral.size() >= 2);
    CHECK(identical(run(mode, MuscleParams(), all_neutral), baseline));
  }
}

TEST_CASE("every effect: at its defaults it acts at the stage it declares, on the channels it declares",
          "[effects][catalog][every_effect]") {
  const std::set<std::string> channels(measured_channels().begin(), measured_channels().end());
  for (const EffectPtr& e : every_effect()) {
    const GasMode mode = home(*e);
    INFO(label(*e) << (mode == GasMode::sealed ? ", sealed" : ", supplied"));
    const MuscleParams base = swinging_temperature();
    const Measurement baseline = run(mode, base, {});

    // Stage 1, the model's parameters: changed by a physics effect alone.
    MuscleParams extended = base;
    e->apply_to_params(extended);
    CHECK(identical(run(mode, extended, {}), baseline) == (e->stage() != EffectStage::physics));

    // Stage 2, the muscle's motion: moved by a motion effect alone.
    const ElongationTrajectory crosshead = sealed_bench();
    CHECK(identical(e->apply_to_elongation(crosshead.time(), crosshead.elongation()), crosshead.elongation()) ==
          (e->stage() != EffectStage::motion));

    // Stage 3, what the instruments read: a measurement effect changes exactly the channels it
    // names; any other changes none there, and the force (which every test measures) through the
    // muscle, with `channels_changed` empty for "every channel".
    Measurement truth = baseline;  // Measurement::channel is not const
    Measurement read = baseline;
    e->apply_to_measurement(read);
    std::set<std::string> read_differently;
    for (const std::string& channel : channels) {
      if (!identical(read.channel(channel), truth.channel(channel))) read_differently.insert(channel);
    }
    const std::vector<std::string> declared = e->channels_changed();
    if (e->stage() == EffectStage::measurement) {
      CHECK(read_differently == std::set<std::string>(declared.begin(), declared.end()));
      CHECK_FALSE(declared.empty());
    } else {
      CHECK(read_differently.empty());
      CHECK(declared.empty());
      CHECK_FALSE(identical(run(mode, base, {e}).force_N, baseline.force_N));
    }
  }
}

TEST_CASE("every effect: in a supplied test it changes the driving pressure exactly when it says it reads it",
          "[effects][catalog][every_effect]") {
  const SuppliedBench bench = supplied_bench();
  for (const EffectPtr& e : every_effect()) {
    if (!e->acts_in(GasMode::supplied, nullptr)) continue;
    INFO(label(*e));
    std::vector<double> driving = bench.gauge_pressure_Pa;
    e->apply_to_supplied_pressure(bench.crosshead.time(), driving);
    CHECK(identical(driving, bench.gauge_pressure_Pa) == !e->reads_supplied_pressure());
  }
}
