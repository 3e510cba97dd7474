// fiber_compliance: fibres of axial stiffness EA stretch under their tension T, the force
// conjugate to their length, to b' = b (1 + T / EA); the muscle's force is the virtual work of
// the shape with fibres of that length. Checked against the potential itself (gas, bladder and
// fibres), a closed form of the hoop balance, the inextensible limit and the sensitivities.

#include <cmath>
#include <cstddef>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

namespace {

/// A sealed, isothermal muscle (the default gas, n = 1) with fibres of stiffness `ea` [N].
MuscleParams compliant(double ea) {
  MuscleParams p;
  p.extensions.fiber_compliance_per_N = 1.0 / ea;
  return p;
}

/// The bladder's strain energy E_b [J] at the strains of `shape`, from its definition
/// dE_b = V_rubber (sigma_l deps_l + sigma_h deps_h): the polynomials of eqs. 3.1.12-3.1.13
/// integrated term by term.
double bladder_energy(const BraidGeometry& geometry, const BladderLaw& law, const MuscleShape& shape) {
  const double strain_l = shape.cylinder_length / geometry.deflated_cylinder_length() - 1.0;
  const double strain_h = shape.diameter / geometry.build().bladder_diameter_m - 1.0;
  double energy = 0.0;
  for (std::size_t k = 0; k < law.longitudinal_Pa.size(); ++k) {
    const double power = static_cast<double>(k + 1);
    energy +=
        law.longitudinal_Pa[k] * std::pow(strain_l, power) / power + law.hoop_Pa[k] * std::pow(strain_h, power) / power;
  }
  return bladder_reference_volume(geometry) * energy;
}

/// The potential of the sealed isothermal muscle at length L with fibres of length b [J], the
/// work the crosshead has done on it up to a constant: the bladder's strain energy, the gas's free
/// energy -m R T ln(V + V_dead), the atmosphere's p_atm V, and the fibres' springs
/// N EA (b - b0)^2 / (2 b0).
double potential(const MuscleModel& model, double length, double fiber) {
  const BraidGeometry& geometry = model.geometry();
  const MuscleParams& p = model.params();
  ShapeHint hint;
  const MuscleShape shape = geometry.shape_from(hint, length, fiber, ShapeParts::kinematics);
  const double volume = shape.gas_volume + model.dead_volume();
  const double gas = -model.gas_mass() * p.gas.gas_constant_J_per_kgK * p.gas.ambient_temperature_K * std::log(volume) +
                     p.gas.atmospheric_pressure_Pa * shape.gas_volume;
  const double rest = geometry.fiber_length();
  const double springs =
      p.build.fiber_count / p.extensions.fiber_compliance_per_N * (fiber - rest) * (fiber - rest) / (2.0 * rest);
  return bladder_energy(geometry, p.bladder, shape) + gas + springs;
}

}  // namespace

TEST_CASE("fiber_compliance: the tension balances the stretch, and the force is the potential's virtual work",
          "[effects][fiber_compliance][physics]") {
  const double ea = 150.0;
  const MuscleModel model(compliant(ea), table_c2_90());
  const double rest = model.geometry().fiber_length();
  const double fibers = model.params().build.fiber_count;
  for (const double length : {0.165, 0.19, 0.215}) {
    const MuscleOutputs out = model.evaluate(length, 0.0, model.initial());
    const double fiber = out.fiber_length_m;
    INFO("L = " << length << " m: b' / b - 1 = " << fiber / rest - 1.0 << ", T = " << out.fiber_tension_N
                << " N, F = " << out.forces.total << " N");
    REQUIRE(out.forces.friction == 0.0);
    REQUIRE(fiber / rest - 1.0 > 1e-3);  // these fibres do stretch, by T / EA ~ 1 %
    // The tension solves its own equation: EA (b' / b - 1) = T.
    CHECK_REL(ea * (fiber / rest - 1.0), out.fiber_tension_N, 1e-13);
    // b' is where the potential, springs included, is stationary in the fibre length: its
    // central difference in b' (step 1e-6 m: truncation h^2 U''' ~ 1e-9 N, rounding
    // eps |U| / h ~ 1e-7 N of the fibres' N T ~ 300 N; measured below 1e-9) is zero, and without
    // the springs it is -N T: the tension is the force conjugate to the fibres' length.
    const double h = 1e-6;
    const double pull = (potential(model, length, fiber + h) - potential(model, length, fiber - h)) / (2.0 * h);
    CHECK(std::abs(pull) <= 1e-7 * fibers * out.fiber_tension_N);
    // The force is dU/dL of that potential along b'(L) (the envelope theorem: U is stationary in
    // b', so dU/dL is its partial at fixed b'): a fourth-order central difference of step 1e-5 m
    // between evaluations each at its own balance (truncation h^4 F^(5) / 30, negligible; rounding
    // eps |U| / h ~ 1e-8 N with |U| ~ 400 J, over F of 10-330 N; measured below 1e-9).
    const double step = 1e-5;
    const auto along = [&](double moved) {
      return potential(model, moved, model.evaluate(moved, 0.0, model.initial()).fiber_length_m);
    };
    const double virtual_work = (8.0 * (along(length + step) - along(length - step)) -
                                 (along(length + 2.0 * step) - along(length - 2.0 * step))) /
                                (12.0 * step);
    CHECK_REL(out.forces.total, virtual_work, 1e-8);
  }
}

TEST_CASE(
    "fiber_compliance: a flat-ended braid without bladder has the hoop balance's tension, and a free-inflated "
    "one stretches its fibres",
    "[effects][fiber_compliance][physics]") {
  // A thin cylinder of N fibres making n turns, at gauge pressure p, without bladder or end
  // cones: a cut along its length Lm crosses the fibres 2 n N times at the braid angle theta, so
  // p D Lm = 2 n N T sin(theta), sin(theta) = pi n D / b', and N T = p Lm b' / (2 pi n^2). Its
  // axial force -p dV/dL = p (3 Lm^2 - b'^2) / (4 pi n^2) vanishes at Lm = b' / sqrt(3), where
  // the fibres carry N T = p b'^2 / (2 sqrt(3) pi n^2): a free-inflated muscle's fibres stretch,
  // though it carries no axial force (a spring in series with the axial force would not).
  const double ea = 200.0;
  MuscleParams p = compliant(ea);
  p.build.cone_generator_m = 0.0;
  p.bladder = BladderLaw::none();
  p.friction.fiber_fiber_coefficient = p.friction.fiber_bladder_coefficient = 0.0;
  const MuscleModel model(p, InitialState{0.16, 300e3});
  const double n = p.build.fiber_revolutions;
  const double fibers = p.build.fiber_count;
  const double pi = 3.14159265358979323846;
  for (const double length : {0.12, 0.16, 0.2}) {
    const MuscleOutputs out = model.evaluate(length, 0.0, model.initial());
    INFO("L = " << length << " m");
    CHECK_REL(fibers * out.fiber_tension_N,
              out.gauge_pressure_Pa * out.shape.cylinder_length * out.fiber_length_m / (2.0 * pi * n * n), 1e-12);
  }
  const auto axial = [&](double length) { return model.evaluate(length, 0.0, model.initial()).forces.total; };
  std::uintmax_t iterations = 100;
  const auto root =
      boost::math::tools::toms748_solve(axial, 0.10, 0.2, boost::math::tools::eps_tolerance<double>(50), iterations);
  const MuscleOutputs free = model.evaluate(0.5 * (root.first + root.second), 0.0, model.initial());
  const double b = free.fiber_length_m;
  const double rest = model.geometry().fiber_length();
  INFO("free at L = " << free.shape.length << " m, gauge " << free.gauge_pressure_Pa
                      << " Pa, b' / b - 1 = " << b / rest - 1.0);
  CHECK(std::abs(free.forces.total) < 1e-9);
  CHECK_REL(free.shape.cylinder_length, b / std::sqrt(3.0), 1e-12);
  CHECK_REL(b / rest - 1.0, free.gauge_pressure_Pa * b * b / (2.0 * std::sqrt(3.0) * pi * n * n * fibers * ea), 1e-12);
  CHECK(b / rest - 1.0 > 1e-3);
}

TEST_CASE("fiber_compliance: stiff fibres are the inextensible model", "[effects][fiber_compliance][physics]") {
  const MuscleParams rigid;
  const InitialState initial = table_c2_90();
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  // EA = inf is no compliance at all: the effect leaves the run bit for bit.
  CHECK(identical(measure(rigid, initial, crosshead, {"fiber_compliance:stiffness_N=inf"}),
                  measure(rigid, initial, crosshead, {})));
  // As EA grows the compliant model, its own solve and rates, goes over to the inextensible one
  // linearly in 1 / EA: the force's departure at 1e-8 / N is a tenth of that at 1e-7 / N (to
  // the departure's own second order, 1e-6 of it), and the fibres' stretch is T / EA.
  const MuscleModel stiff_model(rigid, initial);
  MuscleWorkspace warm;
  for (const double length : {0.17, 0.19, 0.2165}) {
    INFO("L = " << length << " m");
    const MuscleOutputs inextensible = stiff_model.evaluate(length, 2.5e-3, stiff_model.initial());
    std::vector<double> departure;
    for (const double compliance : {1e-7, 1e-8}) {
      MuscleParams p = rigid;
      p.extensions.fiber_compliance_per_N = compliance;
      const MuscleModel model(p, initial);
      const MuscleOutputs out = model.evaluate(length, 2.5e-3, model.initial());
      CHECK_REL(out.fiber_length_m / model.geometry().fiber_length() - 1.0, compliance * out.fiber_tension_N, 1e-6);
      departure.push_back(out.forces.total - inextensible.forces.total);
      CHECK_REL(out.gauge_pressure_Pa, inextensible.gauge_pressure_Pa, 4e-6);  // measured 4e-7 at 1e-7 / N
    }
    CHECK(departure[0] < 0.0);  // stretched fibres let the braid widen less than the rigid one: less force
    CHECK_REL(departure[1], 0.1 * departure[0], 1e-4);
    // Fibres whose stretch is below the resolution of their length (EA = 1e17 N, as a fit may
    // try on its way to infinity) are the inextensible ones to rounding.
    MuscleParams p = rigid;
    p.extensions.fiber_compliance_per_N = 1e-17;
    const MuscleModel model(p, initial);
    const MuscleOutputs out = model.evaluate(length, 2.5e-3, model.initial());
    CHECK_REL(out.forces.total, inextensible.forces.total, 1e-12);
    CHECK_REL(out.rate[State::temperature_K] + 1.0, inextensible.rate[State::temperature_K] + 1.0, 1e-12);
  }
  MuscleParams p = rigid;
  p.extensions.fiber_compliance_per_N = 1e-17;
  CHECK_REL(Simulator().run(MuscleModel(p, initial), crosshead).force_N.back(),
            Simulator().run(stiff_model, crosshead).force_N.back(), 1e-9);
}

TEST_CASE("fiber_compliance: inflated freely and sealed, the muscle carries no force at rest",
          "[effects][fiber_compliance][physics]") {
  // The thesis's protocol (table 3.4): inflated with no load, sealed where the force is zero.
  // Compliant fibres stretch under the tension the inflation puts in them, so the muscle seals
  // longer than the rigid braid does; sealed at the rigid braid's free length it would push.
  const MuscleParams rigid;
  for (const double stiffness_N : {60.0, 300.0}) {
    for (const double gauge_Pa : {100e3, 300e3}) {
      INFO("EA = " << stiffness_N << " N, " << gauge_Pa << " Pa");
      MuscleParams p = compliant(stiffness_N);
      const InitialState sealed = inflated_and_sealed(p, gauge_Pa);
      const MuscleModel model(p, sealed);
      CHECK(std::abs(model.evaluate(sealed.length_m, 0.0, model.initial()).forces.total) < 1e-6);
      const InitialState inextensible = inflated_and_sealed(rigid, gauge_Pa);
      CHECK(sealed.length_m > inextensible.length_m);
      const MuscleModel at_rigid_length(p, inextensible);
      CHECK(at_rigid_length.evaluate(inextensible.length_m, 0.0, at_rigid_length.initial()).forces.total < -1e-3);
    }
  }
  // Fibres too stiff to stretch seal where the rigid braid does.
  const InitialState stiff = inflated_and_sealed(compliant(1e17), 200e3);
  CHECK_REL(stiff.length_m, inflated_and_sealed(rigid, 200e3).length_m, 1e-12);
}

TEST_CASE("fiber_compliance: the same crosshead travel gives less force and a lower pressure",
          "[effects][fiber_compliance]") {
  const MuscleParams rigid;
  const InitialState initial = table_c2_90();
  const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
  const Measurement m = measure(rigid, initial, crosshead, {"fiber_compliance:stiffness_N=300"});
  const Measurement baseline = measure(rigid, initial, crosshead, {});
  const std::size_t top = tops(m.elongation_m).front();
  const std::size_t quarter = top / 4;
  const double drop_top = 1.0 - m.force_N[top] / baseline.force_N[top];
  const double drop_quarter = 1.0 - m.force_N[quarter] / baseline.force_N[quarter];
  INFO("force at the top " << m.force_N[top] << " N vs " << baseline.force_N[top] << " N (" << drop_top
                           << " lower); at a quarter stroke " << drop_quarter << " lower");
  // Fibres that stretch under the hoop stress let the muscle widen as the pressure rises, so the
  // gas is compressed less as the muscle is stretched, and pulls less.
  CHECK(drop_quarter > 0.0);
  CHECK(drop_top > drop_quarter);
  CHECK(m.gauge_pressure_Pa[top] < baseline.gauge_pressure_Pa[top]);
  // Both start from the same inflation pressure at the same length.
  CHECK_REL(m.gauge_pressure_Pa.front(), baseline.gauge_pressure_Pa.front(), 1e-9);
}

TEST_CASE("fiber_compliance: the forward sensitivity to the compliance agrees with central differences",
          "[effects][fiber_compliance][sim][sensitivities]") {
  // The parameter: EA = 300 N / theta, theta = 1 (a fit's coordinate of order one). CVODES's
  // difference quotient of the right-hand side (step 1e-6 of theta) against central differences
  // of two runs at rtol 1e-11 and steps 1e-4 (truncation ~1e-8, the runs' error ~1e-7 of the slope).
  const ElongationTrajectory trajectory = thesis_protocol(0.04, 2.5e-3, 2);
  const auto model = [](double theta) {
    MuscleParams p;
    p.gas.process = GasProcess::heat_transfer;
    p.gas.heat_transfer_time_constant_s = 2.0;
    p.extensions.fiber_compliance_per_N = theta / 300.0;
    return MuscleModel(p, table_c2_90());
  };
  const auto simulator = [](double tolerance) {
    SimulatorConfig config;
    config.relative_tolerance = tolerance;
    config.absolute_tolerance_K = tolerance;
    return Simulator(config);
  };
  const double step = 1e-6;
  const SensitivityResult r = simulator(1e-8).run_sensitivities(model(1.0), {model(1.0 + step)}, {step}, trajectory);
  const double d = 1e-4;
  const SimulationResult up = simulator(1e-11).run(model(1.0 + d), trajectory);
  const SimulationResult down = simulator(1e-11).run(model(1.0 - d), trajectory);
  const auto gap = [d](const std::vector<double>& derivative, const std::vector<double>& plus,
                       const std::vector<double>& minus) {
    double largest = 0.0;
    double worst = 0.0;
    for (std::size_t k = 0; k < plus.size(); ++k) {
      const double central = (plus[k] - minus[k]) / (2.0 * d);
      largest = std::max(largest, std::abs(central));
      worst = std::max(worst, std::abs(derivative[k] - central));
    }
    return worst / largest;
  };
  // Measured 1e-6 (force, pressure) and 1.5e-5 (temperature, through the integrated heat
  // exchange).
  CHECK(gap(r.derivatives[0].force_N, up.force_N, down.force_N) < 1e-4);
  CHECK(gap(r.derivatives[0].gauge_pressure_Pa, up.gauge_pressure_Pa, down.gauge_pressure_Pa) < 1e-4);
  CHECK(gap(r.derivatives[0].temperature_K, up.temperature_K, down.temperature_K) < 1e-4);
}

TEST_CASE(
    "fiber_compliance: the shape's derivatives in the fibre length and the tension's slopes are their "
    "difference quotients",
    "[effects][fiber_compliance][geometry]") {
  // Central differences of step 1e-6 m of the closure solved afresh: truncation h^2 X''' / 6
  // ~1e-12 of X's scale, rounding ~1e-14 / 1e-6 = 1e-8 of it (the closure's Newton tolerance);
  // 1e-6 leaves room for the smallest derivatives, which are differences of larger terms.
  const BladderLaw law = BladderLaw::thesis();
  const BiaxialStress viscous{3e4, -2e4};
  const double gauge = 250e3;
  const double h = 1e-6;
  for (const double zone : {-1.0, 0.004}) {  // the thesis's cones; flat ends with end zones
    MuscleBuild build;
    if (zone > 0.0) {
      build.cone_generator_m = 0.0;
      build.end_zone_m = zone;
    }
    const BraidGeometry geometry(build);
    const double fiber = 1.013 * geometry.fiber_length();
    const auto shape = [&](double length, double b) {
      ShapeHint hint;
      return geometry.shape_from(hint, length, b, ShapeParts::kinematics);
    };
    const auto derivatives = [&](double length, double b) {
      return geometry.fiber_length_derivatives(shape(length, b), b);
    };
    const auto tension = [&](double length, double b) {
      return total_fiber_tension(geometry, shape(length, b), derivatives(length, b), law, gauge, viscous);
    };
    for (const double length : {0.17, 0.2}) {
      INFO((zone > 0.0 ? "flat ends" : "cones") << ", L = " << length << " m");
      const FiberLengthDerivatives f = derivatives(length, fiber);
      const auto in_b = [&](double (*part)(const MuscleShape&)) {
        return (part(shape(length, fiber + h)) - part(shape(length, fiber - h))) / (2.0 * h);
      };
      CHECK_REL(f.d_diameter, in_b([](const MuscleShape& s) { return s.diameter; }), 1e-6);
      CHECK_REL(f.d_gas_volume, in_b([](const MuscleShape& s) { return s.gas_volume; }), 1e-6);
      const auto up_b = derivatives(length, fiber + h);
      const auto down_b = derivatives(length, fiber - h);
      const auto up_l = derivatives(length + h, fiber);
      const auto down_l = derivatives(length - h, fiber);
      CHECK_REL(f.d2_diameter, (up_b.d_diameter - down_b.d_diameter) / (2.0 * h), 1e-6);
      CHECK_REL(f.d2_gas_volume, (up_b.d_gas_volume - down_b.d_gas_volume) / (2.0 * h), 1e-6);
      CHECK_REL(f.d_diameter_d_length, (up_l.d_diameter - down_l.d_diameter) / (2.0 * h), 1e-6);
      CHECK_REL(f.d_gas_volume_d_length, (up_l.d_gas_volume - down_l.d_gas_volume) / (2.0 * h), 1e-6);
      if (zone < 0.0) {
        CHECK_REL(f.d_cylinder_length, in_b([](const MuscleShape& s) { return s.cylinder_length; }), 1e-6);
        CHECK_REL(f.d2_cylinder_length, (up_b.d_cylinder_length - down_b.d_cylinder_length) / (2.0 * h), 1e-6);
        CHECK_REL(f.d_cylinder_length_d_length, (up_l.d_cylinder_length - down_l.d_cylinder_length) / (2.0 * h), 1e-6);
      } else {
        CHECK(f.d_cylinder_length == 0.0);  // flat ends keep their cylinder's length at a fixed muscle length
      }
      const FiberTensionSlopes slopes =
          total_fiber_tension_slopes(geometry, shape(length, fiber), f, law, gauge, viscous);
      CHECK_REL(slopes.d_fiber, (tension(length, fiber + h) - tension(length, fiber - h)) / (2.0 * h), 1e-6);
      CHECK_REL(slopes.d_length, (tension(length + h, fiber) - tension(length - h, fiber)) / (2.0 * h), 1e-6);
    }
  }
}
