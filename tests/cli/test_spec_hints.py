"""Common slips in a student's own spec get a hint that says what was meant (issue 31 §3):
a key said as one would say it (``rpm``), a unit written inside a string (``"250 rpm"``,
``"101.6 mm"``), a key of another mechanism type (``l3`` on a slider-crank).  Each is one
line naming the file and the key, exit 2."""

import pytest

from tests.conftest import one_line_error, run_inprocess


def _spec(tmp_path, command, kind, old, new):
    """The template of ``mechcli new COMMAND --type KIND`` with the line starting *old*
    replaced by *new*."""
    path = tmp_path / "mine.toml"
    assert run_inprocess("new", command, "--type", kind, "-o", path).returncode == 0
    lines = path.read_text(encoding="utf-8").splitlines()
    at = [i for i, ln in enumerate(lines) if ln.startswith(old)]
    assert len(at) == 1, old
    lines[at[0]] = new
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _error(tmp_path, command, spec):
    proc = run_inprocess(command, spec, "--no-plot", "--quiet", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stdout + proc.stderr
    return one_line_error(proc)


@pytest.mark.parametrize("command, kind, old, new, words", [
    # a speed in rpm said as one says it: the key for it
    ("kin", "four_bar", "omega1 =", "rpm = 300",
     ["[input] rpm", "unknown key 'rpm'", "did you mean 'n1'?"]),
    ("force", "slider_crank", "omega1 =", "speed = 300", ["did you mean 'omega1'?"]),
    ("gear", "pair", "m =", "m = 5\nrpm = 960\npower_kW = 3", ["did you mean 'n1_rpm'?"]),
])
def test_a_key_said_as_one_says_it_suggests_the_key_meant(tmp_path, command, kind, old, new,
                                                         words):
    line = _error(tmp_path, command, _spec(tmp_path, command, kind, old, new))
    assert line.startswith("mechcli: error: ") and "mine.toml" in line
    for w in words:
        assert w in line


@pytest.mark.parametrize("command, kind, old, new, words", [
    # a speed in rpm inside a string: omega1 is rad/s, the rpm key is n1
    ("kin", "slider_crank", "omega1 =", 'omega1 = "250 rpm"',
     ["[input] omega1", "not a string with a unit", "omega1 is in rad/s",
      "n1 = 250", "got '250 rpm' (a string)"]),
    # a length with its unit: lengths are plain numbers in the file's units
    ("kin", "four_bar", "l1 =", 'l1 = "101.6 mm"',
     ["[mechanism] l1", "every length is in the file's units = \"mm\"", "(l1 = 101.6)"]),
    # another length unit than the file's: the number in the file's, or change units
    ("kin", "four_bar", "l1 =", 'l1 = "4 in"',
     ["l1 = 101.6, or l1 = 4 with units = \"in\""]),
    # an angle in radians: angles are degrees, converted (0.5 rad = 28.6479°)
    ("kin", "four_bar", "start =", 'start = "0.5 rad"', ["angles are in degrees (start = 28.6479)"]),
    # the rpm key itself with its unit
    ("kin", "general", "n1 =", 'n1 = "170 rpm"', ["n1 is in rpm: n1 = 170"]),
    # a cam's speed has no rpm key: the value in rad/s (100 rpm = 100·π/30 = 10.472 rad/s)
    ("cam", "translating_roller", "omega =", 'omega = "100 rpm"', ["omega = 10.472"]),
    # a length in a gear table
    ("gear", "spur", "m =", 'm = "5 mm"', ["[spur] m", "(m = 5)"]),
    # a number in quotes
    ("kin", "four_bar", "l1 =", 'l1 = "101.6"', ["a number, not a string", "(l1 = 101.6)"]),
    # an item of an array
    ("grashof", "fourbar", "lengths =", 'lengths = [28, "52 mm", 50, 72]',
     ["lengths[1]", "not a string with a unit"]),
])
def test_a_unit_inside_a_string_says_how_units_are_given(tmp_path, command, kind, old, new,
                                                        words):
    line = _error(tmp_path, command, _spec(tmp_path, command, kind, old, new))
    for w in words:
        assert w in line, line


@pytest.mark.parametrize("command, kind, old, new, words", [
    ("kin", "slider_crank", "l2 =", "l2 = 300\nl3 = 200",
     ["[mechanism] l3", 'a key of type = "slider_crank" (', "slider_crank has no l3"]),
    ("kin", "four_bar", "l4 =", "l4 = 304.8\ne = 5", ["four_bar has no e"]),
    # keys of the general form on a preset, a slider-crank's model on a four-bar
    ("force", "four_bar", "l4 =", "l4 = 1200\nframe = 4", ["four_bar has no frame"]),
    ("kin", "four_bar", "l4 =", 'l4 = 304.8\nmodel = "approximate"', ["four_bar has no model"]),
    # a key of another dyad type, of another synthesis kind
    ("kin", "general", "block =", "block = 2\nlength = 50",
     ["[mechanism.dyad.0] length", "RPR has no length"]),
    ("synth", "function", "x0 =", "x0 = 1\nK = 1.2", ["function has no K"]),
])
def test_a_key_of_another_type_is_named_so(tmp_path, command, kind, old, new, words):
    line = _error(tmp_path, command, _spec(tmp_path, command, kind, old, new))
    for w in words:
        assert w in line, line
    assert "did you mean" not in line    # not a different key of this type


def test_a_plain_misspelling_still_gets_its_did_you_mean(tmp_path):
    line = _error(tmp_path, "kin", _spec(tmp_path, "kin", "slider_crank", "l2 =", "l22 = 300"))
    assert "unknown key 'l22'" in line and "did you mean 'l2'?" in line
