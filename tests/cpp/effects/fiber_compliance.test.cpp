// fiber_compliance: the braid shorter by F Lym / (N EA), and the muscle softer at high force.

#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include "approx.hpp"
#include "effect_test_support.hpp"

using namespace pamkit_test;

TEST_CASE("fiber_compliance: the braid is shorter by F Lym / (N EA), and the muscle is softer at high force",
          "[effects][fiber_compliance]") {
  const double ea = 300.0;
  MuscleParams compliant;
  compliant.extensions.fiber_compliance_per_N = 1.0 / ea;
  const MuscleParams rigid;
  const InitialState initial = table_c2_90();
  const MuscleModel model(compliant, initial);
  const MuscleModel rigid_model(rigid, initial);
  const double lym = model.geometry().fiber_length();
  const double fibers = compliant.build.fiber_count;

  SECTION("the series spring, at rest") {
    for (const double length : {0.17, 0.19, 0.2165}) {
      const MuscleOutputs out = model.evaluate(length, 0.0, model.initial());
      INFO("length " << length << " m: force " << out.forces.total << " N, braid " << out.braid_length_m << " m");
      REQUIRE(out.forces.friction == 0.0);
      // The fibers' tensions sum to the force; each stretches by T Lym / EA.
      CHECK_REL(length - out.braid_length_m, out.forces.total * lym / (fibers * ea), 1e-9);
      // The same force is what the rigid muscle makes at the braid's length.
      CHECK_REL(out.forces.total, rigid_model.evaluate(out.braid_length_m, 0.0, rigid_model.initial()).forces.total,
                1e-12);
    }
  }

  SECTION("the same crosshead travel gives less force, the more so the higher the force") {
    const ElongationTrajectory crosshead = thesis_protocol(0.05, 2.5e-3, 1, 0.1);
    const Measurement m = measure(rigid, initial, crosshead, {"fiber_compliance:stiffness_N=300"});
    const Measurement baseline = measure(rigid, initial, crosshead, {});
    const std::size_t top = tops(m.elongation_m).front();
    const std::size_t quarter = top / 4;
    const double drop_top = 1.0 - m.force_N[top] / baseline.force_N[top];
    const double drop_quarter = 1.0 - m.force_N[quarter] / baseline.force_N[quarter];
    INFO("force at the top " << m.force_N[top] << " N vs " << baseline.force_N[top] << " N (" << drop_top
                             << " lower); at a quarter stroke " << drop_quarter << " lower");
    CHECK(drop_quarter > 0.0);
    CHECK(drop_top > drop_quarter);
    // The braid travels less than the crosshead, so the gas is compressed less.
    CHECK(m.gauge_pressure_Pa[top] < baseline.gauge_pressure_Pa[top]);
  }
}
