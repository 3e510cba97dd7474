"""An Instron Bluehill export of several specimens: every specimen's block is found and
labelled by its "Specimen Number"; one is read when named, and none is guessed."""

import csv
from pathlib import Path

import numpy as np
import pytest

from pamkit.cli import main
from pamkit.io.experiment import load_experiment
from pamkit.io.guards import ExperimentError
from pamkit.io.logger import LoggerError, read_machine_csv
from pamkit.io.machine import read_machine_export

# Three specimens in Bluehill's layout (data/experiments/machines/instron_bluehill.csv's, a block
# per specimen after a blank line): 11 samples each, 0.1 s apart, 0 -> 2.5 mm, and specimen n
# loaded with 10 n N + 2 N/mm times the extension, so that the values say which block was read.
THREE = Path(__file__).parent / "fixtures" / "instron_bluehill_3_specimens.csv"


@pytest.mark.parametrize("specimen", ["1", "2", "3"])
def test_each_specimen_is_read_when_named(specimen):
    export = read_machine_export(THREE, specimen)
    assert export.format == "instron_bluehill"
    assert export.specimens == ["1", "2", "3"]
    assert export.specimen == specimen
    np.testing.assert_allclose(export.columns["time_s"], np.arange(11) * 0.1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(export.columns["extension_m"], np.arange(11) * 0.25e-3, rtol=0, atol=1e-12)
    expected_N = 10.0 * int(specimen) + 2.0 * np.arange(11) * 0.25
    np.testing.assert_allclose(export.columns["force_N"], expected_N, rtol=0, atol=1e-12)


def test_several_specimens_and_none_named_is_refused_naming_them():
    with pytest.raises(ExperimentError, match=r"3_specimens.csv: holds 3 specimens \(1, 2, 3\): choose one"):
        read_machine_export(THREE)
    with pytest.raises(ExperimentError, match=r"3_specimens.csv: no specimen '4'; it holds 1, 2, 3"):
        read_machine_export(THREE, "4")
    # As `pamkit align` reads it.
    with pytest.raises(LoggerError, match=r"holds 3 specimens \(1, 2, 3\): choose one \(pamkit align --specimen"):
        read_machine_csv(THREE)
    assert read_machine_csv(THREE, "3")["force_N"][0] == 30.0


def test_a_file_of_one_specimen_needs_no_choice(thesis_dir):
    one = thesis_dir.parent / "machines" / "instron_bluehill.csv"  # the sample export
    export = read_machine_export(one)
    assert (export.specimens, export.specimen) == (["1"], "1")
    np.testing.assert_array_equal(read_machine_export(one, "1").columns["force_N"], export.columns["force_N"])
    with pytest.raises(ExperimentError, match=r"no specimen '2'; it holds 1"):
        read_machine_export(one, "2")


def test_specimens_without_numbers_are_labelled_by_their_place(tmp_path):
    # No "Specimen Number" lines: the blocks are 1, 2 in order. A bad cell in the second block
    # is named by its line in the file.
    block = 'Time,Extension,Load\n"(s)","(mm)","(N)"\n0,0,{0}\n1,1,{0}\n'
    path = tmp_path / "export.csv"
    path.write_text("Instron export\n" + block.format(5) + "\n" + block.format(7))
    assert read_machine_export(path, "2").columns["force_N"].tolist() == [7.0, 7.0]
    path.write_text("Instron export\n" + block.format(5) + "\n" + block.format(7).replace("1,1,7", "1,x,7"))
    with pytest.raises(ExperimentError, match=r"export.csv:10: column 2 \(extension\) = 'x' is not a number"):
        read_machine_export(path, "2")
    assert read_machine_export(path, "1").columns["force_N"].tolist() == [5.0, 5.0]


def test_an_experiment_names_its_specimen(write_experiment, tmp_path):
    path = write_experiment(toml_test_extra="specimen = 2")
    path.write_text(path.read_text().replace('data = "run.csv"', f'data = "{THREE.as_posix()}"'))
    experiment = load_experiment(path)
    np.testing.assert_allclose(experiment.columns["force_N"][:2], [20.0, 20.5], rtol=0, atol=1e-12)
    path.write_text(path.read_text().replace("specimen = 2", ""))
    with pytest.raises(ExperimentError, match=r"holds 3 specimens \(1, 2, 3\)"):
        load_experiment(path)
    # pamkit's own CSV is one test: a specimen asked of it is a mistake, named.
    path = write_experiment(toml_test_extra='specimen = "2"')
    with pytest.raises(ExperimentError, match=r"run.csv: \[test\] specimen = '2' chooses among a tensile machine"):
        load_experiment(path)
    path = write_experiment(toml_test_extra="specimen = [2]")
    with pytest.raises(ExperimentError, match=r"run.toml: \[test\] specimen = \[2\] must be a specimen's label"):
        load_experiment(path)


def _align_inputs(tmp_path):
    """A logger record (100 Hz, from 20 s before the machine's record to 10 s after, its clock
    23.21 s ahead of the machine's) of a sealed muscle stretched in three triangles of 16 s to
    10, 6 and 8 mm (unequal: one offset fits), and a machine export of three specimens of which
    the second is that test; the others are stretched otherwise."""
    t = np.arange(0, 48.0, 0.1)
    peak_mm = np.array([10.0, 6.0, 8.0])[np.minimum(t // 16, 2).astype(int)]
    stretch_mm = peak_mm * (1 - np.abs(((t / 16) % 1) * 2 - 1))
    shapes = {"1": 4 * np.sin(t / 3) ** 2, "2": stretch_mm, "3": np.minimum(t, 12.0)}
    machine = tmp_path / "machine.csv"
    with machine.open("w", newline="") as handle:
        writer = csv.writer(handle, quoting=csv.QUOTE_ALL)
        writer.writerow(["Sample I.D.", "PAM1-035kPa"])
        for label, extension in shapes.items():
            writer.writerows([["Specimen Number", label], [], ["Time", "Extension", "Load"], ["(s)", "(mm)", "(N)"]])
            writer.writerows([f"{a:.2f}", f"{b:.4f}", f"{5 * b:.3f}"] for a, b in zip(t, extension))
            writer.writerow([])
    logger = tmp_path / "logger.csv"
    machine_t = np.arange(-20.0, 58.0, 0.01)
    logger_t = machine_t + 23.21
    pressure = 35 + 0.8 * np.interp(machine_t, t, stretch_mm)  # the sealed gas follows the length
    with logger.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["time_s", "pressure_kPa", "temperature_C"])
        writer.writerows([f"{a:.2f}", f"{p:.4f}", "22.85"] for a, p in zip(logger_t, pressure))
    return logger, machine


def test_align_aligns_the_specimen_named(tmp_path, capsys, thesis_dir):
    logger, machine = _align_inputs(tmp_path)
    muscle = thesis_dir / "pam1_035kPa_95pct.toml"
    output = tmp_path / "aligned.toml"
    arguments = ["align", str(logger), str(machine), "-o", str(output), "--muscle", str(muscle)]
    assert main(arguments) == 2
    assert "machine.csv: holds 3 specimens (1, 2, 3): choose one (pamkit align --specimen" in capsys.readouterr().err
    assert main([*arguments, "--specimen", "2"]) == 0
    printed = capsys.readouterr().out
    found = float(printed.split("logger time = machine time + ")[1].split(" s")[0])
    assert abs(found - 23.21) <= 0.01, printed  # one logger sample
    experiment = load_experiment(output)
    assert "(specimen 2)" in experiment.description
    # Specimen 2's loads (5 N/mm of its stretch), from where the logger's record begins.
    np.testing.assert_allclose(experiment.columns["force_N"], 5e3 * experiment.elongation_m, rtol=0, atol=1e-9)
    assert experiment.elongation_m.max() == pytest.approx(0.01, abs=1e-6)
