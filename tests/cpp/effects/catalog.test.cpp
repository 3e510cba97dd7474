// The catalog as users drive it: effects parsed from `--effect` text, errors that name the bad
// part, which tests an effect can act in, a user's own C++ effect, and effects combined. What
// every effect must do is in every_effect.test.cpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

namespace {

using namespace pamkit_test;

// The value of numeric parameter `key` of `e`.
double parameter(const Effect& e, const std::string& key) {
  for (const EffectParameter& p : e.parameters()) {
    if (p.name == key) return p.value;
  }
  FAIL("effect " << e.name() << " has no parameter " << key);
  return 0.0;
}

// The message of the InvalidParameter that parsing `spec` throws ("" if it does not throw).
std::string parse_error(const std::string& spec) {
  try {
    effect(spec);
  } catch (const InvalidParameter& error) {
    return error.what();
  }
  return "";
}

// A user's effect, written against the public interface only: the load cell reads `factor`
// times the force.
class LoadCellGain : public Effect {
 public:
  std::string name() const override { return "load_cell_gain"; }
  std::string description() const override { return "gain error of the load cell"; }
  std::vector<EffectParameter> parameters() const override {
    return {{"factor", factor_, "1", 0.5, 2.0, 0.98, 1.02, "reading per true newton"}};
  }
  void set(const std::string& key, const std::string& value) override {
    if (key != "factor") throw InvalidParameter("load_cell_gain has no parameter '" + key + "' (factor)");
    factor_ = std::stod(value);
  }
  void apply_to_measurement(Measurement& m) const override {
    for (double& f : m.force_N) f *= factor_;
  }

 private:
  double factor_ = 1.0;
};

// An effect that only exists in supplied tests.
class RegulatorDroop : public Effect {
 public:
  std::string name() const override { return "regulator_droop"; }
  std::string description() const override { return "a pressure regulator's droop"; }
  std::vector<EffectParameter> parameters() const override { return {}; }
  void set(const std::string& key, const std::string&) override { throw InvalidParameter("no parameter " + key); }
  bool acts_in(GasMode mode, std::string* why_not) const override {
    if (mode == GasMode::supplied) return true;
    if (why_not) *why_not = "regulator_droop needs a regulator: the sealed muscle has none";
    return false;
  }
};

// Two cycles with holds, so that every stage has something to act on.
ElongationTrajectory bench() { return thesis_protocol(0.05, 2.5e-3, 2, 0.1, 2.0); }

}  // namespace

TEST_CASE("catalog: holds the effects the diagnosis has been measured with", "[effects][catalog]") {
  // What the benches, the documentation and the users' files rely on: the model's physical
  // extensions, what real muscles add (a braid that goes slack, rate-independent pressurise/vent
  // hysteresis, commercial muscles' loops at rest: a friction with memory, Maxwell-slip) and the
  // instruments' errors (the load cell's tare and nonlinearity, the thermometer's offset). None
  // may go missing; a new effect is its header, its test and its line in catalog.hpp, not an entry
  // here. What each effect must do is checked for every entry of the catalog, whatever its name,
  // in every_effect.test.cpp; the documentation's table is written from the catalog.
  const std::vector<std::string> relied_on{"bladder_viscoelasticity",
                                           "braid_slack",
                                           "dead_volume",
                                           "fiber_compliance",
                                           "fixture_slack",
                                           "heat_transfer",
                                           "leak",
                                           "load_cell",
                                           "pressure_hysteresis",
                                           "sensor_lag",
                                           "sensor_offset",
                                           "slip_hysteresis",
                                           "thermometer",
                                           "time_skew"};
  const std::vector<std::string> names = EffectCatalog::builtin().names();
  for (const std::string& name : relied_on) {
    INFO(name);
    CHECK(std::find(names.begin(), names.end(), name) != names.end());
  }
}

TEST_CASE("catalog: parse sets the values written in the text", "[effects][catalog]") {
  CHECK(parameter(*effect("heat_transfer:time_constant_s=3.5"), "time_constant_s") == 3.5);
  CHECK(parameter(*effect("dead_volume:volume_fraction=0.05"), "volume_fraction") == 0.05);
  CHECK(parameter(*effect("leak:time_constant_s=inf"), "time_constant_s") == HUGE_VAL);
  CHECK(parameter(*effect("fiber_compliance:stiffness_N=2e2"), "stiffness_N") == 200.0);
  CHECK(parameter(*effect("fixture_slack:slack_m=0.0015"), "slack_m") == 0.0015);
  const EffectPtr visco = effect("bladder_viscoelasticity:time_constant_s=4,strength=0.7");
  CHECK(parameter(*visco, "time_constant_s") == 4.0);
  CHECK(parameter(*visco, "strength") == 0.7);
  const EffectPtr lag = effect("sensor_lag:channel=gauge_pressure_Pa,time_constant_s=0.5");
  CHECK(lag->options().at("channel") == "gauge_pressure_Pa");
  CHECK(parameter(*lag, "time_constant_s") == 0.5);
  const EffectPtr skew = effect("time_skew:offset_s=-1.5,channel=force_N");
  CHECK(skew->options().at("channel") == "force_N");
  CHECK(parameter(*skew, "offset_s") == -1.5);
  const EffectPtr offset = effect("sensor_offset:offset_Pa=-3e3,gain=1.02");
  CHECK(parameter(*offset, "offset_Pa") == -3e3);
  CHECK(parameter(*offset, "gain") == 1.02);
  // A bare name gives the defaults; a later key overrides an earlier one.
  CHECK(parameter(*effect("leak"), "time_constant_s") == 1000.0);
  CHECK(parameter(*effect("leak:time_constant_s=10,time_constant_s=20"), "time_constant_s") == 20.0);
}

TEST_CASE("catalog: bad text throws InvalidParameter naming the bad part", "[effects][catalog]") {
  struct Bad {
    std::string spec;
    std::vector<std::string> named;  // what the message must contain
  };
  const std::vector<Bad> cases{
      {"heat_transfr", {"unknown effect", "heat_transfr", "heat_transfer"}},  // and lists the known ones
      {":time_constant_s=1", {"unknown effect"}},
      {"heat_transfer:tau=2", {"heat_transfer", "'tau'", "time_constant_s"}},
      {"heat_transfer:time_constant_s=abc", {"time_constant_s", "'abc'", "not a number"}},
      {"heat_transfer:time_constant_s=2s", {"time_constant_s", "'2s'", "not a number"}},
      {"heat_transfer:time_constant_s=", {"time_constant_s", "not a number"}},
      {"heat_transfer:time_constant_s=-1", {"time_constant_s", "-1", "outside the allowed range"}},
      {"heat_transfer:time_constant_s=nan", {"time_constant_s", "outside the allowed range"}},
      {"dead_volume:volume_fraction=11", {"volume_fraction", "11", "outside the allowed range"}},
      {"sensor_offset:gain=0", {"gain", "outside the allowed range"}},
      {"leak:time_constant_s=0", {"time_constant_s", "outside the allowed range"}},
      {"sensor_lag:channel=force", {"channel", "'force'", "force_N, gauge_pressure_Pa, temperature_K"}},
      {"time_skew:channel=elongation_m", {"channel", "'elongation_m'"}},
      {"time_skew:offset_s", {"'offset_s'", "key=value"}},
      {"fixture_slack:=1", {"'=1'", "key=value"}},
      {"heat_transfer:channel=force_N", {"heat_transfer", "'channel'"}},  // no channel on a gas effect
  };
  for (const Bad& bad : cases) {
    const std::string message = parse_error(bad.spec);
    INFO("spec '" << bad.spec << "': " << (message.empty() ? "did not throw InvalidParameter" : message));
    REQUIRE_FALSE(message.empty());
    for (const std::string& part : bad.named) CHECK(message.find(part) != std::string::npos);
  }
  CHECK_THROWS_AS(EffectCatalog().add("", [] { return EffectPtr(); }), InvalidParameter);
  // A number set as a number is checked as text is.
  CHECK_THROWS_WITH(EffectCatalog::builtin().make("leak")->set_value("tau", 1.0),
                    Catch::Matchers::Contains("has no parameter 'tau'"));
  CHECK_THROWS_WITH(EffectCatalog::builtin().make("leak")->set_value("time_constant_s", -1.0),
                    Catch::Matchers::Contains("outside the allowed range"));
}

TEST_CASE("catalog: split reads the grammar parse reads, settings in the order written", "[effects][catalog]") {
  using Settings = std::vector<std::pair<std::string, std::string>>;
  const auto [name, settings] = EffectCatalog::split("sensor_lag:time_constant_s=2,channel=force_N,time_constant_s=3");
  CHECK(name == "sensor_lag");
  CHECK(settings == Settings{{"time_constant_s", "2"}, {"channel", "force_N"}, {"time_constant_s", "3"}});
  CHECK(EffectCatalog::split("leak") == std::make_pair(std::string("leak"), Settings{}));
  // An unknown name is the catalog's to refuse, not the grammar's; a bad item is the grammar's.
  CHECK(EffectCatalog::split("no_such_effect:x=1").first == "no_such_effect");
  CHECK_THROWS_WITH(EffectCatalog::split("leak:time_constant_s"), Catch::Matchers::Contains("is not key=value"));
  // parse is make and set over split's settings: the last of a repeated key wins.
  const EffectPtr lag =
      EffectCatalog::builtin().parse("sensor_lag:time_constant_s=2,channel=force_N,time_constant_s=3");
  CHECK(parameter(*lag, "time_constant_s") == 3.0);
  CHECK(lag->options().at("channel") == "force_N");
}

TEST_CASE("catalog: effects that cannot act in a test say why", "[effects][catalog]") {
  const EffectCatalog catalog = EffectCatalog::builtin();
  for (const std::string& name : catalog.names()) {
    // Below: supplied tests and tables only.
    if (name == "braid_slack" || name == "pressure_hysteresis" || name == "slip_hysteresis") continue;
    std::string why = "untouched";
    INFO(name);
    CHECK(catalog.make(name)->acts_in(GasMode::sealed, &why));
    CHECK(why == "untouched");
  }
  std::string why_slack;
  CHECK_FALSE(catalog.make("braid_slack")->acts_in(GasMode::sealed, &why_slack));
  CHECK(why_slack.find("taut") != std::string::npos);
  CHECK(catalog.make("braid_slack")->acts_in(GasMode::supplied, nullptr));
  CHECK_FALSE(catalog.make("pressure_hysteresis")->acts_in(GasMode::sealed, nullptr));
  CHECK(catalog.make("pressure_hysteresis")->acts_in(GasMode::supplied, nullptr));
  std::string why_slip;
  CHECK_FALSE(catalog.make("slip_hysteresis")->acts_in(GasMode::sealed, &why_slip));
  CHECK(why_slip.find("sealed") != std::string::npos);
  CHECK(catalog.make("slip_hysteresis")->acts_in(GasMode::supplied, nullptr));
  // The gas effects need a sealed gas; the viscoelastic and compliant bladder and braid need
  // the dynamic model; the fixture and the instruments act on any test.
  for (const std::string name : {"heat_transfer", "dead_volume", "leak"}) {
    std::string why;
    INFO(name);
    CHECK_FALSE(catalog.make(name)->acts_in(GasMode::supplied, &why));
    CHECK(why.find(name) != std::string::npos);
    CHECK(why.find("supplied") != std::string::npos);
  }
  for (const std::string name : {"bladder_viscoelasticity", "fiber_compliance"}) {
    std::string why;
    INFO(name);
    CHECK_FALSE(catalog.make(name)->acts_in(GasMode::supplied, &why));
    CHECK(why.find("dynamic") != std::string::npos);
  }
  for (const std::string name : {"fixture_slack", "sensor_lag", "time_skew", "sensor_offset"}) {
    INFO(name);
    CHECK(catalog.make(name)->acts_in(GasMode::supplied, nullptr));
  }
  // simulate_measurement runs sealed tests, and refuses an effect that cannot act there.
  try {
    simulate_measurement(MuscleParams(), table_c2_90(), bench(), {std::make_shared<RegulatorDroop>()});
    FAIL("simulate_measurement accepted an effect that cannot act in a sealed test");
  } catch (const InvalidParameter& error) {
    CHECK(std::string(error.what()) == "regulator_droop needs a regulator: the sealed muscle has none");
  }
}

TEST_CASE("catalog: a user's C++ effect is added, parsed from text and simulated like a built-in one",
          "[effects][catalog]") {
  EffectCatalog catalog = EffectCatalog::builtin();
  catalog.add("load_cell_gain", [] { return std::make_shared<LoadCellGain>(); });
  CHECK(catalog.names().size() == EffectCatalog::builtin().names().size() + 1);
  const EffectPtr gain = catalog.parse("load_cell_gain:factor=1.5");
  CHECK(parameter(*gain, "factor") == 1.5);
  CHECK_THROWS_AS(catalog.parse("load_cell_gain:gain=2"), InvalidParameter);

  const Measurement truth = simulate_measurement(MuscleParams(), table_c2_90(), bench(), {});
  const Measurement m = simulate_measurement(MuscleParams(), table_c2_90(), bench(), {gain});
  for (std::size_t k = 0; k < truth.time_s.size(); ++k) CHECK(m.force_N[k] == 1.5 * truth.force_N[k]);
  CHECK(identical(m.gauge_pressure_Pa, truth.gauge_pressure_Pa));
  // The catalog is an ordinary object: the built-in one is unchanged.
  CHECK_THROWS_AS(EffectCatalog::builtin().make("load_cell_gain"), InvalidParameter);
}

TEST_CASE("catalog: effects combine, each at its stage and in order", "[effects][catalog]") {
  SECTION("one at each stage equals the stages applied by hand") {
    const std::vector<std::string> specs{"heat_transfer:time_constant_s=2", "fixture_slack:slack_m=0.001",
                                         "sensor_lag:channel=temperature_K,time_constant_s=8"};
    const Measurement combined = measure(MuscleParams(), table_c2_90(), bench(), specs);

    MuscleParams params;
    effect(specs[0])->apply_to_params(params);
    const ElongationTrajectory crosshead = bench();
    const ElongationTrajectory muscle(crosshead.time(),
                                      effect(specs[1])->apply_to_elongation(crosshead.time(), crosshead.elongation()));
    const SimulationResult r = precise_simulator().run(MuscleModel(params, table_c2_90()), muscle);
    Measurement by_hand;
    by_hand.time_s = r.time_s;
    by_hand.elongation_m = crosshead.elongation();
    by_hand.force_N = r.force_N;
    by_hand.gauge_pressure_Pa = r.gauge_pressure_Pa;
    by_hand.temperature_K = r.temperature_K;
    effect(specs[2])->apply_to_measurement(by_hand);
    CHECK(identical(combined, by_hand));
    // And each one did something.
    const Measurement baseline = measure(MuscleParams(), table_c2_90(), bench(), {});
    CHECK_FALSE(identical(combined.temperature_K, baseline.temperature_K));
    CHECK_FALSE(identical(combined.force_N, baseline.force_N));
  }

  SECTION("two on the gas: dead volume and a leak, in either order; the leak still decays as exp(-t/tau)") {
    std::vector<double> time;
    for (int k = 0; k <= 60; ++k) time.push_back(k);
    const ElongationTrajectory still(time, std::vector<double>(time.size(), 0.0));
    const Measurement a =
        measure(MuscleParams(), table_c2_90(), still, {"dead_volume:volume_fraction=0.3", "leak:time_constant_s=30"});
    const Measurement b =
        measure(MuscleParams(), table_c2_90(), still, {"leak:time_constant_s=30", "dead_volume:volume_fraction=0.3"});
    CHECK(identical(a, b));
    // The orifice lets out mass in proportion to the gauge pressure and the whole gas volume,
    // hose included, so at a fixed length the gauge pressure decays as exp(-t/tau) still.
    for (std::size_t k = 0; k < time.size(); ++k) {
      INFO("t = " << time[k] << " s");
      CHECK_REL(a.gauge_pressure_Pa[k], 236.63e3 * std::exp(-time[k] / 30.0), 1e-6);  // tolerance as in the leak test
    }
  }

  SECTION("two on one channel apply in the order given") {
    const Measurement truth = measure(MuscleParams(), table_c2_90(), bench(), {});
    const Measurement skew_then_offset = measure(MuscleParams(), table_c2_90(), bench(),
                                                 {"time_skew:offset_s=1", "sensor_offset:offset_Pa=5e3,gain=1.1"});
    const Measurement offset_then_skew = measure(MuscleParams(), table_c2_90(), bench(),
                                                 {"sensor_offset:offset_Pa=5e3,gain=1.1", "time_skew:offset_s=1"});
    Measurement expected = truth;
    effect("time_skew:offset_s=1")->apply_to_measurement(expected);
    effect("sensor_offset:offset_Pa=5e3,gain=1.1")->apply_to_measurement(expected);
    CHECK(identical(skew_then_offset, expected));
    // Affine and a shift commute up to rounding (interpolation of gain p + offset).
    for (std::size_t k = 0; k < truth.time_s.size(); ++k) {
      CHECK_REL(offset_then_skew.gauge_pressure_Pa[k], skew_then_offset.gauge_pressure_Pa[k], 1e-12);
    }
  }
}
