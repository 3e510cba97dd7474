#pragma once
/// \file
/// The braid's shape at every sample of a prescribed trajectory, solved once for one build: the
/// closure solves of a run's output path, which dominate a long record's simulation, shared by
/// every run along the same lengths that differs only in pressure, friction, bladder law, gas
/// or physics that leaves the braid's length alone (a diagnosis's hundreds of runs of one test).

#include <cstddef>
#include <vector>

#include "pamkit/sim/model.hpp"
#include "pamkit/sim/trajectory.hpp"

namespace pamkit {

/// The MuscleShape (ShapeParts::kinematics_and_braid_angle: lengths, volumes, their derivatives
/// and the cylinder's braid angle) at each sample length L_k = L0 + e_k of a trajectory, for one
/// build. Immutable once built, so one table may serve many runs on many threads at once
/// (Simulator::run, simulate_measurement), as a const MuscleModel does.
///
/// The shapes are solved in sample order, each closure started from the previous sample's
/// (BraidGeometry::shape_from), as a run's output path solves them: a run that reads the table
/// reports the same numbers, bit for bit, as one that solves the shapes itself.
class ShapeTable {
 public:
  /// \param build            the muscle's build
  /// \param initial_length_m muscle length at zero elongation L0 [m]
  /// \param trajectory       the muscle's elongation e_k [m]: after any motion-stage effect (a
  ///                         fixture's slack), which a run compares in `applies_to`
  /// \throws InvalidParameter for an invalid build; InvalidInput naming the first sample whose
  ///         length is outside the braid's range.
  ShapeTable(const MuscleBuild& build, double initial_length_m, const ElongationTrajectory& trajectory);

  /// Whether a run of `model` along `trajectory` may read its output shapes here: the model's
  /// build is this table's field for field, every sample's length L0 + e_k (the model's L0) is
  /// this table's bit for bit, and the fibers are inextensible (with fiber compliance the
  /// braid's shape depends on the fibers' tension, so on the state, and no table can hold it). Costs a
  /// comparison per sample, no closure solve.
  bool applies_to(const MuscleModel& model, const ElongationTrajectory& trajectory) const;

  /// Number of samples.
  std::size_t size() const { return shapes_.size(); }
  /// The shape at sample `k` (k < size(), unchecked: the run has checked the sizes).
  const MuscleShape& shape(std::size_t k) const { return shapes_[k]; }
  /// Muscle length L0 + e_k at each sample [m].
  const std::vector<double>& length_m() const { return length_m_; }
  /// The build the shapes belong to.
  const MuscleBuild& build() const { return build_; }
  /// Muscle length at zero elongation L0 [m].
  double initial_length_m() const { return initial_length_m_; }

 private:
  MuscleBuild build_;
  double initial_length_m_;
  std::vector<double> length_m_;
  std::vector<MuscleShape> shapes_;
};

/// Whether two builds are the same, field for field and bit for bit: a shape solved for one is
/// the other's.
inline bool same_build(const MuscleBuild& a, const MuscleBuild& b) {
  bool same = true;
  MuscleBuild::for_each_field(
      [&](const char*, double MuscleBuild::*member, const FieldInfo&) { same = same && a.*member == b.*member; });
  return same;
}

inline ShapeTable::ShapeTable(const MuscleBuild& build, double initial_length_m, const ElongationTrajectory& trajectory)
    : build_(build), initial_length_m_(initial_length_m) {
  const BraidGeometry geometry(build_);
  const auto& elongation = trajectory.elongation();
  length_m_.reserve(elongation.size());
  shapes_.reserve(elongation.size());
  ShapeHint hint;
  for (std::size_t k = 0; k < elongation.size(); ++k) {
    // The length as the simulator's output path forms it (simulator.cpp, BlockRecorder::record).
    const double length = initial_length_m_ + elongation[k];
    if (!(length > geometry.min_length() && length < geometry.max_length())) {
      throw InvalidInput(detail::message("ShapeTable: trajectory sample ", k, " (t = ", trajectory.time()[k],
                                         " s, elongation ", elongation[k], " m) gives muscle length ", length,
                                         " m, outside the braid's range (", geometry.min_length(), ", ",
                                         geometry.max_length(), ") m"));
    }
    length_m_.push_back(length);
    shapes_.push_back(geometry.shape_from(hint, length, ShapeParts::kinematics_and_braid_angle));
  }
}

inline bool ShapeTable::applies_to(const MuscleModel& model, const ElongationTrajectory& trajectory) const {
  if (model.params().extensions.fiber_compliance_per_N != 0.0) return false;
  if (!same_build(model.params().build, build_)) return false;
  const auto& elongation = trajectory.elongation();
  if (elongation.size() != length_m_.size()) return false;
  const double initial = model.initial_state().length_m;
  for (std::size_t k = 0; k < elongation.size(); ++k) {
    if (initial + elongation[k] != length_m_[k]) return false;
  }
  return true;
}

}  // namespace pamkit
