// The muscle-parameters file: what is written reads back as the same doubles, and every kind of
// bad file is refused with a message that names the file, the line and column, and the key.

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "pamkit/io/params_file.hpp"

namespace {

using namespace pamkit;
using Catch::Matchers::Contains;

/// A file in the system's temporary folder, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((std::filesystem::temp_directory_path() / ("pamkit_params_" + name + ".toml")).string()) {}
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }
  std::string text() const {
    std::ifstream in(path_);
    std::stringstream out;
    out << in.rdbuf();
    return out.str();
  }
  void write(const std::string& text) const { std::ofstream(path_) << text; }

 private:
  std::string path_;
};

/// Every field moved off its default to a value with no short decimal form (1/3 of a percent up,
/// or a seventh of the way into its range from a default at the bottom): a writer that rounds
/// would not read back the same doubles.
template <class Struct>
void perturb(Struct& object) {
  Struct::for_each_field([&](const char*, auto Struct::*member, const FieldInfo& info) {
    double& value = object.*member;
    value =
        value != 0.0 ? value * (1.0 + 0.01 / 3.0) : info.min + (std::min(info.max, info.min + 1.0) - info.min) / 7.0;
  });
}

template <class Struct>
void check_same_fields(const Struct& read, const Struct& written) {
  Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo&) {
    INFO(Struct::kName << "." << name);
    CHECK(read.*member == written.*member);  // exactly: the file keeps every bit
  });
}

MuscleParams awkward_params(const BladderLaw& bladder) {
  MuscleParams params;
  perturb(params.build);
  perturb(params.friction);
  perturb(params.gas);
  perturb(params.extensions);
  params.gas.process = GasProcess::heat_transfer;
  // End zones belong to flat flanges: the perturbed end zone with the cones taken off, on the
  // construction that is not the default.
  params.build.cone_generator_m = 0.0;
  params.build.construction = Construction::embedded;
  params.bladder = bladder;
  return params;
}

BladderLaw scaled_thesis(double scale) {
  BladderLaw law = BladderLaw::thesis();
  for (double& c : law.longitudinal_Pa) c *= scale;
  for (double& c : law.hoop_Pa) c *= scale;
  return law;
}

void check_same(const MuscleParamsFile& read, const MuscleParams& written) {
  check_same_fields(read.params.build, written.build);
  check_same_fields(read.params.friction, written.friction);
  check_same_fields(read.params.gas, written.gas);
  check_same_fields(read.params.extensions, written.extensions);
  CHECK(read.params.gas.process == written.gas.process);
  CHECK(read.params.build.construction == written.build.construction);
  CHECK(read.params.bladder.form == written.bladder.form);
  CHECK(read.params.bladder.longitudinal_Pa == written.bladder.longitudinal_Pa);
  CHECK(read.params.bladder.hoop_Pa == written.bladder.hoop_Pa);
  CHECK(read.params.bladder.shear_modulus_Pa == written.bladder.shear_modulus_Pa);
}

/// 1-based number of the first line of `text` that starts with `start`.
int line_of(const std::string& text, const std::string& start) {
  std::istringstream lines(text);
  int number = 1;
  for (std::string line; std::getline(lines, line); ++number) {
    if (line.rfind(start, 0) == 0) return number;
  }
  FAIL("no line starts with " << start);
  return 0;
}

/// `text` with the line that starts with `start` replaced by `replacement` (removed if empty).
std::string replace_line(const std::string& text, const std::string& start, const std::string& replacement) {
  std::istringstream lines(text);
  std::string out;
  bool found = false;
  for (std::string line; std::getline(lines, line);) {
    if (!found && line.rfind(start, 0) == 0) {
      found = true;
      if (!replacement.empty()) out += replacement + "\n";
    } else {
      out += line + "\n";
    }
  }
  REQUIRE(found);
  return out;
}

/// A valid file (the defaults), edited by `edit`, written to `file`; returns the edited text.
template <class Edit>
std::string edited_defaults(const TempFile& file, Edit edit) {
  write_muscle_params(file.path(), MuscleParams{});
  const std::string text = edit(file.text());
  file.write(text);
  return text;
}

std::string at(const TempFile& file, int line, int column) {
  return file.path() + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
}

}  // namespace

TEST_CASE("a written parameters file reads back as the same MuscleParams", "[io]") {
  TempFile file("round_trip");
  SECTION("the thesis polynomial, scaled as a calibration scales it, with the initial state") {
    const MuscleParams written = awkward_params(scaled_thesis(0.7310585786300049));
    const InitialState initial{0.16712345678901234, 240123.456789};
    write_muscle_params(file.path(), written, initial, "calibrated by a test\nsecond line");
    const MuscleParamsFile read = read_muscle_params_file(file.path());
    check_same(read, written);
    REQUIRE(read.initial.has_value());
    check_same_fields(*read.initial, initial);
    CHECK_THAT(file.text(), Contains("# calibrated by a test\n# second line\n"));
  }
  SECTION("a neo-Hookean membrane, without an initial state") {
    const MuscleParams written = awkward_params(BladderLaw::neo_hookean(1.2345678901234567e6));
    write_muscle_params(file.path(), written);
    const MuscleParamsFile read = read_muscle_params_file(file.path());
    check_same(read, written);
    CHECK_FALSE(read.initial.has_value());
    CHECK_THAT(file.text(), !Contains("longitudinal_Pa"));
  }
  SECTION("every key is one of its struct's fields, with unit and meaning beside it") {
    write_muscle_params(file.path(), MuscleParams{});
    const std::string text = file.text();
    MuscleBuild::for_each_field([&](const char* name, auto, const FieldInfo& info) {
      CHECK_THAT(text, Contains(std::string("\n") + name + " = ") && Contains(info.description));
    });
    CHECK_THAT(text, Contains("process = 'polytropic'"));
    CHECK_THAT(text, Contains("construction = 'sleeve'"));
  }
}

TEST_CASE("a hand-written file: integers are numbers, short coefficient lists leave the higher ones 0", "[io]") {
  TempFile file("hand_written");
  edited_defaults(file, [](std::string text) {
    text = replace_line(text, "fiber_count =", "fiber_count = 48");
    text = replace_line(text, "longitudinal_Pa =", "longitudinal_Pa = [0, 1.5e6]");
    return text;
  });
  const MuscleParams read = read_muscle_params(file.path());
  CHECK(read.build.fiber_count == 48.0);
  CHECK(read.bladder.longitudinal_Pa == std::array<double, 7>{0.0, 1.5e6, 0, 0, 0, 0, 0});
  CHECK(read.bladder.hoop_Pa == BladderLaw::thesis().hoop_Pa);
}

TEST_CASE("a bad parameters file is refused naming file, line, column and key", "[io]") {
  TempFile file("bad");
  SECTION("unknown key") {
    const std::string text =
        edited_defaults(file, [](std::string t) { return replace_line(t, "fiber_count =", "fiber_cont = 48.0"); });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidInput);
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "fiber_cont"), 1) + "unknown key [build] fiber_cont (known: "));
  }
  SECTION("out of the field's range: the FieldInfo message, at the value") {
    const std::string text =
        edited_defaults(file, [](std::string t) { return replace_line(t, "fiber_count =", "fiber_count = -3.0"); });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidParameter);
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "fiber_count"), 15) +
                               "[build] fiber_count: MuscleBuild.fiber_count = -3 1 is outside the allowed range "
                               "[2, 5000]"));
  }
  SECTION("wrong type") {
    const std::string text = edited_defaults(
        file, [](std::string t) { return replace_line(t, "sharpness_s_per_m =", "sharpness_s_per_m = \"fast\""); });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidInput);
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "sharpness_s_per_m"), 21) +
                               "[friction] sharpness_s_per_m must be a number, not a string"));
  }
  SECTION("missing section") {
    edited_defaults(file, [](std::string t) {
      for (const char* key : {"[gas]", "gas_constant", "heat_capacity", "atmospheric", "ambient", "polytropic_index",
                              "heat_transfer_time", "process"}) {
        t = replace_line(t, key, "");
      }
      return t;
    });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidInput);
    CHECK_THROWS_WITH(read_muscle_params(file.path()), Contains(file.path() + ": missing section [gas]"));
  }
  SECTION("missing key: the section's line") {
    const std::string text = edited_defaults(file, [](std::string t) { return replace_line(t, "slack_band_N =", ""); });
    CHECK_THROWS_WITH(read_muscle_params(file.path()), Contains(at(file, line_of(text, "[extensions]"), 1) +
                                                                "missing key [extensions] slack_band_N (["));
  }
  SECTION("unknown section") {
    const std::string text = edited_defaults(file, [](std::string t) { return t + "[muscle]\nlength_m = 0.2\n"; });
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "[muscle]"), 2) + "unknown section [muscle] (known: build,"));
  }
  SECTION("a key of the other bladder form (the keys are visited in name order)") {
    const std::string text = edited_defaults(file, [](std::string t) {
      return replace_line(t, "form =", "form = \"neo_hookean\"\nshear_modulus_Pa = 1e6");
    });
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "hoop_Pa"), 11) +
                               "[bladder] hoop_Pa does not belong to form = \"neo_hookean\""));
  }
  SECTION("too many coefficients") {
    const std::string text = edited_defaults(
        file, [](std::string t) { return replace_line(t, "hoop_Pa =", "hoop_Pa = [1, 2, 3, 4, 5, 6, 7, 8]"); });
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "hoop_Pa"), 11) + "[bladder] hoop_Pa must be a list of 1 to 7"));
  }
  SECTION("a negative shear modulus: BladderLaw's own check, at the value") {
    const std::string text = edited_defaults(file, [](std::string t) {
      t = replace_line(t, "longitudinal_Pa =", "");
      t = replace_line(t, "hoop_Pa =", "");
      return replace_line(t, "form =", "form = \"neo_hookean\"\nshear_modulus_Pa = -5.0");
    });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidParameter);
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "shear_modulus_Pa"), 20) + "[bladder] shear_modulus_Pa: "));
  }
  SECTION("an unknown gas process") {
    const std::string text =
        edited_defaults(file, [](std::string t) { return replace_line(t, "process =", "process = \"adiabatic\""); });
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "process"), 11) +
                               "[gas] process = \"adiabatic\" must be \"polytropic\" or \"heat_transfer\""));
  }
  SECTION("an unknown construction") {
    const std::string text = edited_defaults(
        file, [](std::string t) { return replace_line(t, "construction =", "construction = \"woven\""); });
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(at(file, line_of(text, "construction"), 16) +
                               "[build] construction = \"woven\" must be \"sleeve\" or \"embedded\""));
  }
  SECTION("fields in range that do not fit together: MuscleParams::validate, with the file's name") {
    edited_defaults(file,
                    [](std::string t) { return replace_line(t, "bladder_diameter_m =", "bladder_diameter_m = 0.03"); });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidParameter);
    CHECK_THROWS_WITH(read_muscle_params(file.path()),
                      Contains(file.path() + ": MuscleBuild.bladder_diameter_m = 0.03 m is larger than the braid"));
  }
  SECTION("not TOML: toml++'s message at its place") {
    const std::string text =
        edited_defaults(file, [](std::string t) { return replace_line(t, "length_m =", "length_m = = 0.2"); });
    CHECK_THROWS_AS(read_muscle_params(file.path()), InvalidInput);
    CHECK_THROWS_WITH(read_muscle_params(file.path()), Contains(at(file, line_of(text, "length_m"), 12)));
  }
  SECTION("no such file") {
    CHECK_THROWS_WITH(read_muscle_params(file.path() + ".missing"), Contains(file.path() + ".missing: "));
  }
}

TEST_CASE("parameters out of range are not written", "[io]") {
  TempFile file("invalid_write");
  MuscleParams params;
  params.build.fiber_count = -3;
  CHECK_THROWS_AS(write_muscle_params(file.path(), params), InvalidParameter);
  CHECK_FALSE(std::filesystem::exists(file.path()));
}
