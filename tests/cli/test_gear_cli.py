"""``mechcli gear`` from the command line: outputs, warnings, exit codes and messages."""

import json

import pytest

from tests.conftest import CONFIGS, run_cli, run_inprocess

CH5 = CONFIGS / "ch5"


def _spec(tmp_path, body, name="g.toml"):
    path = tmp_path / name
    path.write_text('command = "gear"\nunits = "mm"\n' + body, encoding="utf-8")
    return path


def test_example_5_4_warns_about_contact_ratio(tmp_path):
    # subprocess smoke test of gear (``python -m mechcli`` end to end); the rest run in-process
    proc = run_cli("gear", CH5 / "ex5-4.toml", "--json", "--no-plot", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    # 例 5-4 prints epsilon = 0.765 (BOOK_5_4 below); half a unit of the last digit
    assert doc["results"]["epsilon_alpha"] == pytest.approx(0.765, abs=5e-4)
    assert any("0.765 < 1" in w for w in doc["warnings"])
    for key in ("a", "a_w", "d1", "d2", "db1", "db2", "da1", "da2", "df1", "df2",
                "alpha_a1_deg", "alpha_a2_deg", "alpha_w_deg", "epsilon_alpha"):
        assert key in doc["results"]
    assert (tmp_path / "gear.csv").read_text().startswith("a_w_mm,alpha_w_deg")


def test_example_5_4_listing_in_chinese(tmp_path):
    proc = run_inprocess("gear", CH5 / "ex5-4.toml", "--lang", "zh", "--quiet", "--no-plot",
                   "--out", tmp_path)
    assert proc.returncode == 0
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    for line in ("直齿圆柱齿轮几何尺寸", "标准中心距", "a = 250.000mm", "db2 = 375.877mm",
                 "alpha1 = 31.321°", "alpha2 = 23.541°", "alpha = 22.888°", "epsilon = 0.765",
                 "已知条件"):
        assert line in text
    # the warning (εα < 1) is on stderr, not in the report handed in (issue 31 §2)
    assert "警告" not in text and "warning" in proc.stderr


BOOK_5_4 = [  # 【例 5-4】 四、运算结果, as printed (OCR "喷合角" is 啮合角)
    ("标准中心距", "a = 250.000mm"), ("实际中心距", "aT = 255.000mm"),
    ("小齿轮分度圆直径", "d1 = 100.000mm"), ("大齿轮分度圆直径", "d2 = 400.000mm"),
    ("小齿轮基圆直径", "db1 = 93.969mm"), ("大齿轮基圆直径", "db2 = 375.877mm"),
    ("小齿轮齿顶圆直径", "da1 = 110.000mm"), ("大齿轮齿顶圆直径", "da2 = 410.000mm"),
    ("小齿轮齿根圆直径", "df1 = 87.500mm"), ("大齿轮齿根圆直径", "df2 = 387.500mm"),
    ("小齿轮齿顶圆压力角", "alpha1 = 31.321°"), ("大齿轮齿顶圆压力角", "alpha2 = 23.541°"),
    ("啮合角", "alpha = 22.888°"), ("重合度", "epsilon = 0.765"),
]


def test_example_5_4_listing_line_for_line(tmp_path):
    proc = run_inprocess("gear", CH5 / "ex5-4.toml", "--lang", "zh", "--quiet", "--no-plot",
                   "--out", tmp_path)
    assert proc.returncode == 0
    lines = (tmp_path / "report.txt").read_text(encoding="utf-8").splitlines()
    start = lines.index("直齿圆柱齿轮几何尺寸")
    got = [tuple(line.split(None, 1)) for line in lines[start + 1:start + 15]]
    assert got == BOOK_5_4


def test_require_continuous_mesh_exits_3(tmp_path):
    proc = run_inprocess("gear", CH5 / "ex5-4.toml", "--set", "pair.require_continuous=true",
                   "--no-plot", "--out", tmp_path)
    assert proc.returncode == 3
    assert "εα = 0.765 < 1" in proc.stderr


def test_forbidden_interference_exits_3(tmp_path):
    ok = run_inprocess("gear", CH5 / "internal-pair.toml", "--json", "--no-plot", "--out", tmp_path)
    assert ok.returncode == 0
    assert any("interference" in w for w in json.loads(ok.stdout)["warnings"])
    proc = run_inprocess("gear", CH5 / "internal-pair.toml", "--set", "pair.forbid_interference=true",
                   "--no-plot", "--out", tmp_path)
    assert proc.returncode == 3
    assert "interference" in proc.stderr and "below its base circle" in proc.stderr


def test_pair_animation_shows_the_gap_in_contact(tmp_path):
    proc = run_inprocess("gear", CH5 / "ex5-4.toml", "--quiet", "--animate", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "pair.gif").read_bytes()[:6] == b"GIF89a"
    assert (tmp_path / "pair.png").stat().st_size > 10000


def test_table_5_1_files_and_layout(tmp_path):
    proc = run_inprocess("gear", CH5 / "ex5-1.toml", "--quiet", "--no-plot", "--lang", "zh",
                   "--set", "involute.digits=6", "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "表 5-1" in text
    row20 = next(line for line in text.splitlines() if line.lstrip().startswith("20.0000"))
    # 表 5-1; closed form inv alpha = tan alpha - alpha at 20°, 20°10′, 20°20′:
    # 0.0149044, 0.0151367, 0.0153724 (rad)
    assert row20.split()[1:4] == ["0.014904", "0.015137", "0.015372"]
    lines = (tmp_path / "involute.csv").read_text().splitlines()
    # header + the table rows of configs/ch5/ex5-1.toml's range and step
    assert lines[0] == "alpha_deg,inv_alpha_rad" and len(lines) == 211
    assert (tmp_path / "curve.csv").exists()


def test_pictures_are_written(tmp_path):
    proc = run_inprocess("gear", CH5 / "gear-cut.toml", "--quiet", "--animate", "--out", tmp_path,
                   "--set", "generation.step_deg=18")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "generation.png").stat().st_size > 10000
    assert (tmp_path / "generation.gif").read_bytes()[:6] == b"GIF89a"


def test_inverse_involute_auto(tmp_path):
    spec = _spec(tmp_path, "[inverse_involute]\ntheta = [1e-12, 0.02, 1.5]\n")
    proc = run_inprocess("gear", spec, "--json", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    # inv alpha = 0.02: alpha = 21.9808° = 21°58′51″ (tan a - a = 0.02 by Newton, and 表 5-1)
    assert res["alpha_dms_2"] == "21°58′51″"
    assert res["iterations"] <= 4 and res["relative_residual"] < 1e-14
    assert res["relative_residual_3"] < 1e-14


def test_book_start_outside_its_region_exits_3(tmp_path):
    spec = _spec(tmp_path, '[inverse_involute]\ntheta = 1.2\nmethod = "book"\n')
    proc = run_inprocess("gear", spec, "--out", tmp_path / "o")
    assert proc.returncode == 3
    assert "book Newton start" in proc.stderr


@pytest.mark.parametrize("body, key, fragment", [
    ("[spur]\nz = 20.5\nm = 5\n", "[spur] z", "an integer in [1, 10000]"),
    ("[spur]\nz = 0\nm = 5\n", "[spur] z", "an integer in [1, 10000]"),
    ("[spur]\nz = 20\nm = -5\n", "[spur] m", "positive"),
    ("[spur]\nz = 20\nm = 5\nalpha_deg = 45\n", "[spur] alpha_deg", "[1, 45)"),
    ("[spur]\nz = 20\nm = 5\nalpa_deg = 20\n", "[spur] alpa_deg", "did you mean 'alpha_deg'"),
    ("[pair]\nz1 = 20\nz2 = 80\nm = 5\na_w = 245\n", "[pair] a_w", ">= 250"),
    ("[worm]\nz1 = 1\nz2 = 40\nd2 = 280\n", "[worm] q", "q or d1"),
    ("[pair]\nz1 = 20\nz2 = 60\nm = 4\ninternal = true\na_w = 81\n", "[pair] a_w",
     "for this internal pair"),
    ("[pair]\nz1 = 20\nz2 = 15\nm = 4\ninternal = true\n", "[pair] z2", "more teeth"),
    ("[pair]\nz1 = 20\nz2 = 80\nm = 5\na_w = [255, 245]\n", "[pair] a_w[1]", ">= 250"),
    ("[pair]\nz1 = 20\nz2 = 80\nm = 5\nalpha_w_deg = [25, 15]\n", "[pair] alpha_w_deg[1]",
     "a' >= 250, got 15 (a' = 243.21)"),
    ("[pair]\nz1 = 20\nz2 = 60\nm = 4\ninternal = true\nalpha_w_deg = 25\n",
     "[pair] alpha_w_deg", "a' <= 80"),
    ("[pair]\nratio = 1.6\na_w = 78\nm = 3\nx1 = 0.5\nx2 = 0.5\n", "[pair] a_w", ">= 80.6863"),
    ("[spur]\nz = 20\nm = 5\nthickness_radii = [50, 40]\n", "[spur] thickness_radii[1]",
     "radii >= rb"),
    ("[spur]\nz = 20\nm = 5\n[pair]\nz1 = 1\n", "", "exactly one problem table"),
    ("[spurr]\nz = 20\n", "spurr", "did you mean 'spur'"),
])
def test_bad_specs_exit_2_naming_the_key(tmp_path, body, key, fragment):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert key in proc.stderr and fragment in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize("body, fragment", [
    ("[spur]\nz = 10\nm = 10\nx = 1.0\nforbid_pointed = true\n", "pointed"),
    ("[spur]\nz = 9\nm = 10\nforbid_undercut = true\n", "undercut"),
    ("[pair]\nratio = 1.7\na_w = 78\nm = 3\n", "not whole"),
    ("[pair]\nz1 = 10\nz2 = 30\nm = 2\nx1 = 1.0\nforbid_pointed = true\n", "pointed tip"),
])
def test_unsolvable_exit_3(tmp_path, body, fragment):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    assert fragment in proc.stderr


@pytest.mark.parametrize("body, key", [
    ("[spur]\nz = 20\nm = 5\ntip_shortening = true\n", "tip_shortening"),   # was NameError, exit 1
    ("[spur]\nz = 20\nm = 5\nanimate = true\n", "animate"),                  # was silently ignored
    ("[involute]\nrb = 50\ncurve_step_deg = 1e-9\n", "curve_step_deg"),      # was MemoryError
    ("[involute]\nrb = 50\ntable_step_deg = 1e-9\n", "table_step_deg"),
])
def test_bad_keys_exit_2(tmp_path, body, key):
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "-q", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert key in proc.stderr and "Traceback" not in proc.stderr
