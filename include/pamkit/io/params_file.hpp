#pragma once
/// \file
/// A muscle's parameters as a TOML file, under the C++ field names: what `pamkit diagnose
/// --params-out` writes after calibrating the model, and what a controller or `pamkit simulate
/// --params` reads back. Header-only: CMake target pamkit::params (`find_package(pamkit COMPONENTS
/// params)`), which needs toml++ 3's headers and nothing of pamkit but pamkit::muscle, so a
/// controller reads a fitted muscle without the compiled library, SUNDIALS or Python.
///
/// The file has one section per part of MuscleParams, each key a field of that part's
/// `for_each_field` list, in SI units:
///
///     [build]        MuscleBuild's fields (length_m, diameter_m, ...), and construction = "sleeve" or
///                    "embedded" (fibres in the membrane: the braid cannot push)
///     [bladder]      form = "polynomial" with longitudinal_Pa = [c0, ..., c6] and
///                    hoop_Pa = [c0, ..., c6] (BladderLaw's coefficients; fewer than seven leave the
///                    higher ones 0), or form = "neo_hookean" with shear_modulus_Pa
///     [friction]     FrictionParams' fields
///     [gas]          GasParams' fields, and process = "polytropic" or "heat_transfer"
///     [extensions]   ModelExtensions' fields
///     [initial]      optional: InitialState's fields (length_m, gauge_pressure_Pa), the state at
///                    zero elongation of the sealed test the parameters were calibrated on
///     [rig]          optional: effects = ["NAME:key=value,...", ...], what a diagnosis found in the
///                    test's fixture and instruments (a time skew, a load cell's offset), as the
///                    effect catalog parses them; not the muscle's, so a controller leaves them out
///                    and `pamkit simulate --params` applies them to predict what the rig reads
///
/// Every section but [initial] and [rig] and every key of a section are required: a file states the whole
/// muscle, so nothing is silently taken from a default. Unknown sections and keys are errors.

#include <optional>
#include <string>
#include <vector>

#include "pamkit/sim/model.hpp"

namespace pamkit {

/// What a muscle-parameters file holds.
struct MuscleParamsFile {
  MuscleParams params;                   ///< the muscle: [build], [bladder], [friction], [gas], [extensions]
  std::optional<InitialState> initial;   ///< [initial], if the file has it
  std::vector<std::string> rig_effects;  ///< [rig] effects: the test rig's effect specs, if the file has them
};

/// Reads and validates a muscle-parameters file.
/// \param path the TOML file.
/// \throws InvalidInput naming the file, line, column and key for a file that cannot be parsed, a
///         missing or unknown section or key, or a value of the wrong type;
///         InvalidParameter (with the same location) for a value outside its field's range, or
///         naming the file for fields that do not fit together (MuscleParams::validate).
inline MuscleParamsFile read_muscle_params_file(const std::string& path);

/// The muscle of a muscle-parameters file (read_muscle_params_file(path).params).
inline MuscleParams read_muscle_params(const std::string& path);

/// Writes `params` (validated first) and, if given, `initial` to `path`, every key with its unit
/// and meaning as a comment, numbers to the digits that read back to the same doubles.
/// \param comment written at the top, each line as a TOML comment (where the parameters come from).
/// \param rig_effects written as [rig] effects when not empty: effect specs ("NAME:key=value,...").
/// \throws InvalidParameter for parameters out of range (nothing is written);
///         InvalidInput if the file cannot be written.
inline void write_muscle_params(const std::string& path, const MuscleParams& params,
                                const std::optional<InitialState>& initial = std::nullopt,
                                const std::string& comment = "", const std::vector<std::string>& rig_effects = {});

}  // namespace pamkit

#include "pamkit/io/params_file.hxx"
