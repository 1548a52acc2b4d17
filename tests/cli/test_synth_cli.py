"""mechcli synth through the command line: the JSON contract, linkage.toml for kin,
defects on the engine, cases, exit codes and messages."""

import json

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, run_json, write_spec as write

CH3 = CONFIGS / "ch3"


def _json(*args):
    return run_json("synth", *args)


def test_ex3_3_json_contract_and_book_values(tmp_path):
    doc = _json(CH3 / "ex3-3.toml", "--out", tmp_path)
    r = doc["results"]
    assert doc["command"] == "synth"
    # 【例 3-3】 计算结果 1/2 (2 decimals): A(200, 0), D(100, 0), AB 223.61, BC 100, CD 223.61
    assert r["A"] == pytest.approx([200.0, 0.0], abs=0.005)
    assert r["D"] == pytest.approx([100.0, 0.0], abs=0.005)
    assert (r["l1"], r["l2"], r["l3"], r["l4"]) == pytest.approx(
        (223.61, 100.0, 223.61, 100.0), abs=0.005)
    # the design on the engine reproduces the three positions of B and C to round-off
    assert r["residual_max"] < 1e-12 and len(r["residuals"]) == 3
    assert isinstance(r["defects"], list) and r["defect_count"] == len(r["defects"])
    assert r["linkage"] == "four_bar" and r["driver"] == "AB"
    assert r["B1"] == pytest.approx([0.0, 100.0]) and r["C1"] == pytest.approx([0.0, 200.0])
    names = {p.split("/")[-1] for p in doc["files"]}
    assert {"synth.csv", "linkage.toml", "report.txt"} <= names


def test_linkage_toml_is_a_kin_spec_of_the_design(tmp_path):
    """The written linkage.toml runs with `mechcli kin`, and its linkage, read by kin's
    reader and solved at the crank angles of the three positions, puts C at the
    prescribed C1, C2, C3 of 【例 3-3】 ((0, 200), (200, 200), (300, 100) mm)."""
    import numpy as np

    from mechcli.core.linkage import DriverMotion, solve
    from mechcli.spec.kin import load_kin_spec

    r = _json(CH3 / "ex3-3.toml", "--out", tmp_path)["results"]
    proc = run_inprocess("kin", tmp_path / "linkage.toml", "--json", "--no-plot", "--out",
                         tmp_path / "kin")
    assert proc.returncode == 0, proc.stderr
    spec = load_kin_spec(tmp_path / "linkage.toml")
    q = np.radians(r["theta1_deg"])
    m = solve(spec.linkage, {1: DriverMotion(q)}, order=0)
    got = m.points["C"].p * 1e3      # m -> mm
    assert np.abs(got - np.array([0 + 200j, 200 + 200j, 300 + 100j])).max() < 1e-9
    # the kin sweep covers the checked motion from position 1 to position 3
    assert spec.input.start <= min(q) + 1e-12 and spec.input.stop >= max(q) - 1e-12


def test_ex3_2_branch_defect_with_the_crank_driving(tmp_path):
    """The book's furnace door (例 3-2), driven by AB, changes assembly mode between its
    two positions: a branch defect, a warning, and the hint that CD can drive it."""
    doc = _json(CH3 / "ex3-2.toml", "--set", 'synthesis.driver="AB"', "--out", tmp_path)
    r = doc["results"]
    assert r["defects"] == ["branch:2"] and r["driver"] == "AB"
    assert any("branch defect" in w for w in doc["warnings"])
    assert any('driver = "CD"' in w for w in doc["warnings"])
    ok = _json(CH3 / "ex3-2.toml", "--out", tmp_path / "cd")["results"]
    assert ok["defects"] == [] and ok["driver"] == "CD" and ok["residual_max"] < 1e-12


def test_cases_give_one_result_each_and_dotted_expected_keys(tmp_path):
    doc = _json(CH3 / "ex3-8.toml", "--out", tmp_path)
    cases = doc["results"]["cases"]
    assert len(cases) == 4
    # 【例 3-8】 (2): l1 = 77 given, the book prints l2 = 218.44, l4 = 276.80
    assert cases[1]["l1"] == pytest.approx(77.0) and cases[1]["l2"] == pytest.approx(218.44,
                                                                                      abs=5e-3)
    names = {p.split("/")[-1] for p in doc["files"]}
    assert {"linkage-1.toml", "linkage-4.toml"} <= names
    # a dotted [expected] key that names no result (there is no fifth case): exit 2
    bad = write(tmp_path, (CH3 / "ex3-8.toml").read_text(encoding="utf-8")
                + '"cases.4.l1" = 1\n', name="bad.toml")
    proc = run_inprocess("synth", bad, "--json", "--no-plot", "--out", tmp_path / "bad")
    assert proc.returncode == 2
    assert "cases.4.l1" in json.loads(proc.stdout)["error"]


@pytest.mark.parametrize("body, code, words", [
    # three collinear positions of B: no circumcentre (exit 3, the reason named)
    # (C turns rigidly with B: |BC| = 5 in every position)
    ('kind = "three_positions"\nB = [[0, 0], [1, 1], [2, 2]]\nC = [[5, 0], [1, 6], [-3, 2]]',
     3, "[synthesis] B: the three positions of the moving pivot of link 1 are on a line"),
    # a pose row of 2 numbers instead of [x, y, phi]
    ('kind = "coupler_poses"\nA = [0, 0]\nD = [63, 0]\nposes = [[10, 32], [36, 39, 29], '
     '[45, 24, 0]]', 2, "poses[0]"),
    # K below 1, and K = 1, are no quick return
    ('kind = "quick_return"\nK = 0.9\nrocker = 290\nswing = 34\ncrank = 77', 2,
     "[synthesis] K: expected a number in [1, 1000], got 0.9"),
    ('kind = "quick_return"\nK = 1\nrocker = 290\nswing = 34\ncrank = 77', 2,
     "expected a time ratio K > 1"),
    # a crank too long for K = 1.25, swing 34°: the reachable range in mm
    ('kind = "quick_return"\nK = 1.25\nrocker = 290\nswing = 34\ncrank = 200', 3,
     "[synthesis] crank:"),
    # the pivot line misses the circle of A
    ('kind = "quick_return"\nK = 1.25\nrocker = 290\nswing = 34\npivot_line = [1, 0, 5000]',
     3, "[synthesis] pivot_line:"),
    # two extra conditions where the K design takes one
    ('kind = "quick_return"\nK = 1.25\nrocker = 290\nswing = 34\ncrank = 77\nframe = 277',
     2, "exactly one extra condition"),
    # K = 50 with a swing of 34°: θ must stay below 90° + 34°/2 = 107°, K below
    # (180 + 107)/(180 − 107) = 287/73 = 3.93151 (by hand); the report words the degrees
    ('kind = "quick_return"\nK = 50\nrocker = 290\nswing = 34\ncrank = 77', 3,
     "[synthesis] K: no crank-rocker has this time ratio with this swing (theta must stay "
     "below 90 degrees + swing/2) (K must lie in (1, 3.93151))"),
    # K = 5: θ = 120° >= 90°, beyond every offset slider-crank (K = 3 is θ = 90°)
    ('kind = "quick_return"\nlinkage = "slider_crank"\nK = 5\nH = 50\ne = 20', 3,
     "[synthesis] K: no offset slider-crank has a limit-position angle of 90 degrees or more "
     "(K >= 3) (K must lie in (1, 3))"),
    # a swing of half a turn
    ('kind = "quick_return"\nK = 1.25\nrocker = 290\nswing = 180\ncrank = 77', 2, "swing"),
    # lg x of x <= 0
    ('kind = "function"\nmethod = "chebyshev"\nfunction = "log10"\nx0 = -1\nxm = 2\n'
     'alpha_m = 60\nphi_m = 90\nalpha0 = 86\nphi0 = 23.5', 3,
     "[synthesis] x0: x0 = -1 .. xm = 2 leaves the domain"),
    # an unknown kind, with a did-you-mean
    ('kind = "three_position"', 2, "three_positions"),
])
def test_bad_problems_exit_with_one_line(tmp_path, body, code, words):
    spec = write(tmp_path, f'command = "synth"\n[synthesis]\n{body}\n')
    proc = run_inprocess("synth", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == code, proc.stderr
    line = one_line_error(proc)
    assert words in line and str(spec) in line


def test_pictures_are_written(tmp_path):
    proc = run_inprocess("synth", CH3 / "ex3-7.toml", "--quiet", "--animate", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    for name in ("positions.png", "error.png", "synth.gif", "error.csv"):
        assert (tmp_path / name).stat().st_size > 1000, name


def test_four_poses_centre_point_curve_passes_the_fixed_pivots(tmp_path):
    """The four poses of configs/ch3/burmester-four-poses.toml come from the four-bar
    A(0, 0), D(60, 0): its fixed pivots are centre points, so the centre-point curve
    in burmester.csv passes through both (within the curve's sampling)."""
    import csv

    proc = run_inprocess("synth", CH3 / "burmester-four-poses.toml", "--quiet", "--out",
                         tmp_path)
    assert proc.returncode == 0, proc.stderr
    with open(tmp_path / "burmester.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    pts = [complex(float(r["x_centre_mm"]), float(r["y_centre_mm"])) for r in rows]
    circ = [complex(float(r["x_circle_mm"]), float(r["y_circle_mm"])) for r in rows]
    for pivot, moving in ((0j, 20j), (60 + 0j, 45 + 45j)):
        i = min(range(len(pts)), key=lambda j: abs(pts[j] - pivot))
        # neighbouring samples are a few mm apart near the pivots
        assert abs(pts[i] - pivot) < 3.0
        # and the circle point of that sample is near the dyad's moving pivot B1 / C1
        assert abs(circ[i] - moving) < 3.0
    assert (tmp_path / "burmester.png").stat().st_size > 1000


# -- found by an independent review of the first version --------------------------------
@pytest.mark.parametrize("body, words", [
    # a slider that never moves: was exit 0 with l1 = 5.6e-17 mm (kin refused linkage.toml)
    ('kind = "slider_function"\ntheta1 = [60, 85, 120]\ns = [36, 36, 36]',
     "[synthesis] s: the slider positions are all the same"),
    # B nearly collinear: the circumcentre 5e10 mm away (kin refused linkage.toml)
    ('kind = "three_positions"\nB = [[0, 0], [10, 1e-9], [20, 0]]\n'
     'C = [[0, 10], [10, 10.000000001], [20, 10]]', "a pivot practically at infinity"),
    # two equal poses (phi one turn apart): was exit 0 with meaningless curves
    ('kind = "burmester"\nposes = [[0, 0, 0], [0, 0, 360], [1, 2, 30], [3, 1, 50]]',
     "[synthesis] poses: poses 1 and 2 are the same pose"),
    # exp of 1000 overflows: was a numpy RuntimeWarning and a wrong reason
    ('kind = "function"\nmethod = "chebyshev"\nfunction = "exp"\nx0 = 0\nxm = 1000\n'
     'alpha_m = 60\nphi_m = 90\nalpha0 = 86\nphi0 = 23.5', "(its values overflow)"),
])
def test_degenerate_designs_are_exit_3_naming_the_key(tmp_path, body, words):
    spec = write(tmp_path, f'command = "synth"\n[synthesis]\n{body}\n')
    proc = run_inprocess("synth", spec, "--quiet", "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    assert words in one_line_error(proc)
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


def test_a_misspelt_condition_is_named_with_a_did_you_mean(tmp_path):
    spec = write(tmp_path, 'command = "synth"\n[synthesis]\nkind = "quick_return"\nK = 1.25\n'
                 'rocker = 290\nswing = 34\ncrnak = 77\n')
    line = one_line_error(run_inprocess("synth", spec, "--quiet", "--out", tmp_path / "o"))
    assert "[synthesis] crnak:" in line and "did you mean 'crank'?" in line


def test_a_title_with_brackets_is_text_and_warnings_go_to_stderr(tmp_path):
    """A title "door [/bold] closer" was rich markup: exit 1 after the files were
    written.  The defect warnings of 例 3-4 went to stdout with the table."""
    from tests.conftest import run_cli
    text = (CH3 / "ex3-4.toml").read_text(encoding="utf-8").replace(
        'title = "', 'title = "door [/bold] closer ', 1)
    spec = write(tmp_path, text)
    proc = run_cli("synth", spec, "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    assert "door [/bold] closer" in proc.stdout
    assert "branch defect" in proc.stderr and "branch defect" not in proc.stdout
    # report.txt is what is handed in: the machine's warnings stay on stderr (issue 31 §2)
    assert "branch defect" not in (tmp_path / "o" / "report.txt").read_text(encoding="utf-8")


def test_the_boundary_slider_crank_has_a_dead_point_and_kin_still_runs(tmp_path):
    """The slides' exam answer (a + e = b exactly) has a dead point at the crank's top:
    reported as a circuit defect, and linkage.toml asks kin to skip it (partial)."""
    doc = _json(CH3 / "slides-exam3-stroke.toml", "--out", tmp_path)
    assert doc["results"]["defects"] == ["circuit"]
    assert any("dead point at theta1 = 270 deg" in w for w in doc["warnings"])
    assert "partial = true" in (tmp_path / "linkage.toml").read_text(encoding="utf-8")
    proc = run_inprocess("kin", tmp_path / "linkage.toml", "--quiet", "--no-plot", "--out",
                         tmp_path / "kin")
    assert proc.returncode == 0, proc.stderr


def test_no_driver_advice_for_a_function_generator(tmp_path):
    """A function generator's input is its crank: `driver` is no key of its kind, so a
    defect there must not advise driver = "CD" (it did, and the key was refused)."""
    spec = write(tmp_path, 'command = "synth"\n[synthesis]\nkind = "function"\n'
                 'method = "chebyshev"\nfunction = "polynomial"\ncoeffs = [0, 1, 0.5]\n'
                 'x0 = 0\nxm = 1\nalpha_m = 60\nphi_m = 90\n')
    doc = _json(spec, "--out", tmp_path / "o")
    assert doc["results"]["defects"]            # this design has one (origins 0, 0)
    assert not any("driver" in w for w in doc["warnings"])


def test_ex3_3_is_an_antiparallelogram(tmp_path):
    """【例 3-3】's design has parallelogram lengths (223.61, 100, 223.61, 100) but AB and CD
    cross (at (66.7, 66.7) mm in position 1): the crossed assembly, an antiparallelogram."""
    r = _json(CH3 / "ex3-3.toml", "--out", tmp_path)["results"]
    assert r["type"] == "antiparallelogram" and r["cranks"] == [1, 3]


def test_warnings_name_their_spec(tmp_path):
    """A warning on stderr starts with the spec's path, so that a line of a parallel batch
    can be traced to its spec (issue 18 item 5)."""
    proc = run_inprocess("synth", CH3 / "ex3-4.toml", "--quiet", "--no-plot", "--out", tmp_path)
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert lines and all(ln.startswith(f"mechcli: warning: {CH3 / 'ex3-4.toml'}: ")
                         for ln in lines)
