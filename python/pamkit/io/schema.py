"""The experiment file's schema: its sections, the kinds of test and their columns, and the
[test] keys with their meaning. Declared once here; the reader (experiment.py), the writers, the
templates and the reference read them from this list."""

# Experiment kinds: a time series, or a static table of settled rows whose columns (as a file
# names them) are all required.
SERIES_KIND = "series"
TABLE_COLUMNS = {
    "isometric_map": ("length_m", "pressure_kPa", "force_N"),
    "free_inflation": ("pressure_kPa", "length_m", "diameter_m"),
    "isotonic": ("pressure_kPa", "length_m"),  # or contraction_m from the deflated length; time_s optional
}
KINDS = (SERIES_KIND, *TABLE_COLUMNS)

# [test] keys, their meaning, and whether a time series needs them (a static table does not).
TEST_KEYS = {
    "inflation_pressure_kPa": (True, "gauge pressure after inflation, before the first stretch [kPa]"),
    "ambient_temperature_C": (True, "ambient temperature, the gas's initial temperature [°C]"),
    "data": (True, "CSV file, relative to the TOML file"),
    "kind": (False, f"{' or '.join(repr(k) for k in KINDS)} (default {SERIES_KIND!r})"),
    "gas": (False, '"sealed" (default) or "supplied"'),
    "initial_length_m": (False, "muscle length at zero elongation [m]"),
    "load_N": (False, "isotonic: the constant load the muscle carries [N] (or unknown in [calibrate])"),
    "load_mass_kg": (False, "isotonic time series: the hanging load's mass [kg]; the length follows its motion"),
    "description": (False, "free text: where the test comes from"),
    "zero": (False, "a run with no air (CSV, relative to the TOML): its means zero the load cell and transducer"),
    "preload_N": (False, "supplied: the force the deflated muscle was mounted with; sets its length [N]"),
    "force_range_N": (False, "[lowest, highest] force the load cell reads; it clips beyond [N]"),
    "pressure_range_kPa": (False, "[lowest, highest] gauge pressure the transducer reads; it clips beyond [kPa]"),
    "specimen": (False, "a tensile machine's export of several specimens: the one this test is (its Specimen Number)"),
    "ignore_columns": (False, "data columns not to read, as the file names them (a valve's state, a note)"),
    "glitches": (False, 'a time series\' isolated glitches: "leave_out" (default) before the diagnosis, or "keep"'),
}
# [test] ranges of the instruments, by the channel they read (its file column's unit).
RANGE_KEYS = {"force_N": "force_range_N", "pressure_kPa": "pressure_range_kPa"}
# [test] conditions: the range a file may give each in, its unit, and the column of that unit.
TEST_CONDITIONS = {
    "inflation_pressure_kPa": (0.0, 2000.0, "kPa (gauge)", "pressure_kPa"),
    "ambient_temperature_C": (-50.0, 150.0, "°C", "temperature_C"),
}
TABLE_DEFAULTS = {"inflation_pressure_kPa": 0.0, "ambient_temperature_C": 20.0}
# The sections of an experiment file.
EXPERIMENT_SECTIONS = ("muscle", "bladder", "friction", "gas", "calibrate", "uncertain", "test")
# The sections a campaign file shares with its tests, besides [campaign] itself.
CAMPAIGN_SECTIONS = ("campaign", "muscle", "bladder", "friction", "gas", "calibrate", "uncertain")
