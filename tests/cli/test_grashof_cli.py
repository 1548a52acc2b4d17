"""mechcli grashof through the command line: book output format, quick form, batch, exit codes."""

import json
import subprocess
import sys

import pytest

from tests.conftest import CONFIGS, ROOT, one_line_error, run_cli, run_inprocess, write_spec as write

EX31 = CONFIGS / "ch3" / "ex3-1.toml"


def test_ex3_1_report_in_the_books_format(tmp_path):
    proc = run_inprocess("grashof", EX31, "--lang", "zh", "--quiet", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    lines = [ln.split() for ln in text.splitlines()]
    assert ["最长杆", "170.00"] in lines and ["最短杆", "100.00"] in lines
    assert "该机构是双摇杆机构" in text
    en = run_inprocess("grashof", EX31, "--quiet", "--out", tmp_path / "en")
    text = (tmp_path / "en" / "report.txt").read_text(encoding="utf-8")
    assert ["longest", "link", "170.00"] in [ln.split() for ln in text.splitlines()]
    assert "The linkage is a double rocker." in text


def test_json_contract_for_a_crank_rocker(tmp_path):
    # subprocess smoke test of grashof (``python -m mechcli`` end to end)
    proc = run_cli("grashof", "--lengths", "28,52,50,72", "--json", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    r = doc["results"]
    assert doc["command"] == "grashof" and doc["spec"] is None
    assert r["type"] == "crank_rocker" and r["crank"] == 1 and r["grashof"] is True
    assert (r["longest"], r["shortest"]) == (72.0, 28.0)
    for key in ("theta_deg", "psi_deg", "K", "gamma_min_deg", "gamma_min_at_deg",
                "gamma_max_deg"):
        assert isinstance(r[key], float)
    # 习题 3-1's hand calculation (configs/ch3/exercise3-1.toml): AC = l2 ± l1 = 80, 24, cosine
    # rule gives theta = 18.5617°, K = (180 + theta)/(180 - theta) = 1.22995
    assert abs(r["K"] - 1.22995) < 1e-5
    csv = (tmp_path / "grashof.csv").read_text().splitlines()
    assert csv[0].startswith("l1,l2,l3,l4,frame,input,type,crank,grashof,theta_deg")
    assert csv[1].startswith("28,52,50,72,4,1,crank_rocker,1,true,18.56")  # theta, as above


def test_quick_form_frame_input_offset_and_five_bar(tmp_path):
    r = json.loads(run_inprocess("grashof", "--lengths", "10,50,35,30", "--frame", "1", "--input",
                           "2", "--json", "--out", tmp_path).stdout)["results"]
    assert r["type"] == "double_crank" and r["cranks"] == [2, 4]
    r = json.loads(run_inprocess("grashof", "--lengths", "30,60", "--offset", "10", "--json",
                           "--out", tmp_path).stdout)["results"]
    # closed form, offset slider-crank r = 30, l = 60, e = 10: theta = asin(e/(l - r)) -
    # asin(e/(l + r)) = 13.0919°, K = (180 + theta)/(180 - theta) = 1.15687
    assert r["type"] == "crank_slider" and abs(r["K"] - 1.15687) < 1e-5
    for key in ("stroke", "theta_deg", "K", "pressure_angle_max_deg"):
        assert key in r
    r = json.loads(run_inprocess("grashof", "--lengths", "10,21,19,20,5", "--json",
                           "--out", tmp_path).stdout)["results"]
    assert r["class"] == "I" and r["type"] == "triple_crank" and r["cranks"] == [1, 2, 4]


def test_batch_csv_one_row_per_set(tmp_path):
    sets = write(tmp_path, "l1,l2,l3,l4,frame\n100,150,170,110,4\n10,50,35,30,4\n"
                           "10,50,35,30,1\n1,1,1,10,4\n", "sets.csv")
    proc = run_inprocess("grashof", "--batch", sets, "--json", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["results"]["sets"] == 4 and doc["results"]["cannot_close"] == 1
    assert doc["warnings"]
    rows = (tmp_path / "o" / "grashof.csv").read_text().splitlines()
    assert len(rows) == 5
    assert [r.split(",")[6] for r in rows[1:]] == ["double_rocker", "crank_rocker",
                                                   "double_crank", "cannot_close"]


@pytest.mark.parametrize("text, key", [
    ('[fourbar]\nlengths = [10, -50, 35, 30]\n', "lengths[1]"),
    ('[fourbar]\nlengths = [10, "x", 35, 30]\n', "lengths[1]"),
    ('[fourbar]\nlengths = [10, 50, 35]\n', "lengths"),
    ('[fourbar]\nlengths = [10, 50, 35, 30]\nframe = 5\n', "frame"),
    ('[fourbar]\nlengths = [10, 50, 35, 30]\ninput = 2\n', "input"),
    ('[fourbar]\nlengths = [10, 50, 35, 30]\nfrmae = 4\n', "frmae"),
    ('[fivebar]\nlengths = [10, 21, 19, 20]\n', "lengths"),
    ('[fivebar]\nlengths = [10, 21, 19, 20, 5]\ninputs = [1, 2]\n', "inputs"),
    ('[slider_crank]\ncrank = 0\ncoupler = 60\n', "crank"),
    ('[guide_bar]\ncrank = 10\nframe = 20\noffset = -1\n', "offset"),
    ('[mobility]\nframe = 1\n[[mobility.joint]]\nkind = "H"\nlinks = [1, 2, 3]\n', "links"),
    ('[fourbar]\nlengths = [10, 50, 35, 30]\n[guide_bar]\ncrank = 1\nframe = 2\n', ""),
])
def test_bad_specs_exit_2_naming_the_key(tmp_path, text, key):
    spec = write(tmp_path, 'command = "grashof"\nunits = "mm"\n' + text)
    proc = run_inprocess("grashof", spec, "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    msg = one_line_error(proc)
    assert key.split("[")[0].split(".")[-1] in msg
    if key == "frmae":
        assert "did you mean 'frame'" in msg


@pytest.mark.parametrize("args, what", [
    (("--lengths", "10,0,35,30"), "lengths[1]"),
    (("--lengths", "10,abc,35,30"), "lengths[1]"),
    (("--lengths", "10,50,35,30", "--frame", "7"), "--frame"),
    (("--lengths", "10,50,35,30", "--input", "2"), "--input"),
    (("--lengths", "10,50,35"), "lengths"),
    (("--lengths", "1,2,3,4", "--offset", "1"), "--offset"),
    (("--lengths", "30,60", "--frame", "4"), "--frame"),
    (("--lengths", "10,21,19,20,5", "--input", "1"), "--input"),
    (("--lengths", "10,21,19,20,5", "--frame", "6"), "--frame"),
])
def test_bad_quick_form_exits_2(tmp_path, args, what):
    proc = run_inprocess("grashof", *args, "--out", tmp_path)
    assert proc.returncode == 2
    assert what in one_line_error(proc)


def test_bad_batch_rows_exit_2(tmp_path):
    sets = write(tmp_path, "10,50,35,30\n10,50,-1,30\n", "sets.csv")
    proc = run_inprocess("grashof", "--batch", sets, "--out", tmp_path / "o")
    assert proc.returncode == 2 and "row 2" in one_line_error(proc)


@pytest.mark.parametrize("args", [("--lengths", "10,100,20,30"), ("--lengths", "10,20", "--offset",
                                                                    "40"),
                                  ("--lengths", "1,1,1,1,10")])
def test_lengths_that_cannot_close_exit_3(tmp_path, args):
    proc = run_inprocess("grashof", *args, "--out", tmp_path)
    assert proc.returncode == 3
    assert "cannot" in one_line_error(proc)


def test_needs_exactly_one_source_and_no_stray_options(tmp_path):
    assert run_inprocess("grashof", "--out", tmp_path).returncode == 2
    assert run_inprocess("grashof", EX31, "--lengths", "1,2,3,4", "--out", tmp_path).returncode == 2
    for extra in (("--frame", "1"), ("--offset", "3"), ("--units", "cm")):
        proc = run_inprocess("grashof", EX31, *extra, "--out", tmp_path)
        assert proc.returncode == 2 and extra[0] in proc.stderr


def test_mobility_from_a_kin_spec(tmp_path):
    r = json.loads(run_inprocess("grashof", CONFIGS / "ch3" / "mobility-fivebar.toml", "--json",
                           "--out", tmp_path).stdout)["results"]
    # Grübler: F = 3n - 2 P_L - P_H = 3·4 - 2·5 = 2 for the five-bar (4 moving links, 5 R pairs)
    assert (r["F"], r["n"], r["P_L"]) == (2, 4, 5)
    assert sum(j["pairs"] for j in r["joints"] if j["kind"] == "R") == 5
    spec = write(tmp_path, 'command = "grashof"\n[mobility]\nkin = "'
                 + str(CONFIGS / "ch1" / "ex1-1.toml").replace("\\", "/") + '"\n')
    r = json.loads(run_inprocess("grashof", spec, "--json", "--out", tmp_path).stdout)["results"]
    assert r["F"] == 1   # four-bar of 例 1-1: 3·3 - 2·4 = 1


def test_quick_form_imports_neither_matplotlib_nor_scipy(tmp_path):
    code = ("import sys\nfrom mechcli.cli import main\n"
            "try:\n    main(['grashof', '--lengths', '100,150,170,110', '-q', '--out', "
            f"{str(tmp_path)!r}])\n"
            "except SystemExit:\n    pass\n"
            "print(sorted(m for m in ('matplotlib', 'scipy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         check=True).stdout.strip().splitlines()[-1]
    assert out == "[]"


def test_transmission_curve_files(tmp_path):
    spec = CONFIGS / "ch3" / "exercise3-1.toml"
    proc = run_inprocess("grashof", spec, "-q", "--out", tmp_path / "a")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "a" / "transmission.png").stat().st_size > 1000
    assert (tmp_path / "a" / "limits.png").stat().st_size > 1000     # draw = true
    rows = (tmp_path / "a" / "transmission.csv").read_text().splitlines()
    assert rows[0] == "theta1_deg,gamma_deg" and len(rows) == 362   # header + 0° … 360° by 1°
    # gamma_min = 22.7342° at theta1 = 180° (eq. 3-49, the hand calculation in the config)
    assert rows[181].startswith("180,22.734")
    proc = run_inprocess("grashof", spec, "-q", "--no-plot", "--out", tmp_path / "b")
    assert not (tmp_path / "b" / "transmission.png").exists()
    assert not (tmp_path / "b" / "limits.png").exists()
    proc = run_inprocess("grashof", spec, "--lang", "zh", "-q", "--no-plot", "--out", tmp_path / "c")
    assert proc.returncode == 0
    assert "传动角的变化规律" in (tmp_path / "c" / "report.txt").read_text(encoding="utf-8")
