"""The approximate (series in 1/n) slider-crank: ``model = "approximate"``."""

import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from mechcli.core.linkage import approximate, presets
from mechcli.core.linkage.kinematics import Sweep, analyse_sweep, default_quantities

Q = np.radians(np.arange(0.0, 361.0, 1.0))


def _closed_form(q, r, l, w):
    """The books' series (piston from TDC) in mechcli's sign: s3 = l + r - x."""
    n = l / r
    x = r * (1 - np.cos(q)) + r / (2 * n) * np.sin(q) ** 2
    v = w * r * (np.sin(q) + np.sin(2 * q) / (2 * n))
    a = w ** 2 * r * (np.cos(q) + np.cos(2 * q) / n)
    return l + r - x, -v, -a


@pytest.mark.parametrize("n", [3.0, 4.5, 8.0])
def test_series_matches_closed_form(n):
    r, w = 0.1, 10.0
    s, v, a = approximate.motion(Q, r, n * r, w)
    es, ev, ea = _closed_form(Q, r, n * r, w)
    np.testing.assert_allclose(s, es, rtol=0, atol=1e-14)
    np.testing.assert_allclose(v, ev, rtol=0, atol=1e-12)
    np.testing.assert_allclose(a, ea, rtol=0, atol=1e-10)


def test_exact_closed_form_matches_engine():
    r, l, w = 0.1, 0.3, 10.0
    lk = presets.slider_crank(r, l, 0.0)
    sweep = Sweep(1, Q, w, 0.0, {}, True)
    res = analyse_sweep(lk, sweep, default_quantities(lk, 2), 2)
    s, ds, dds = approximate.exact(res.q, r, l)
    np.testing.assert_allclose(res.values["s3"], s, atol=1e-12)
    np.testing.assert_allclose(res.values["v3"], ds * w, atol=1e-10)
    np.testing.assert_allclose(res.values["a3"], dds * w * w, atol=1e-8)


def test_apply_replaces_slide_and_keeps_rod_exact():
    r, l, w = 0.1, 0.3, 10.0
    lk = presets.slider_crank(r, l, 0.0)
    sweep = Sweep(1, Q, w, 0.0, {}, True)
    exact = analyse_sweep(lk, sweep, default_quantities(lk, 2), 2)
    res, diffs = approximate.apply(lk, sweep, exact)
    es, ev, ea = _closed_form(res.q, r, l, w)
    np.testing.assert_allclose(res.values["a3"], ea, atol=1e-10)
    np.testing.assert_array_equal(res.values["theta2"], exact.values["theta2"])
    hi, lo = res.extremes["a3"]
    assert hi.value == pytest.approx(w * w * r * (0.75 - 0.125 / 3), rel=1e-12)
    assert math.degrees(hi.at) == pytest.approx(math.degrees(math.acos(-0.75)), abs=1e-6)
    assert lo.value == pytest.approx(-w * w * r * (1 + 1 / 3), rel=1e-12)
    # largest |a| difference at 90°: ω²r(r/√(l²-r²) - 1/n)
    assert diffs["a"][0] == pytest.approx(w * w * r * (r / math.sqrt(l * l - r * r) - 1 / 3),
                                          rel=1e-9)


def test_error_shrinks_like_one_over_n_cubed():
    """The first neglected term is r sin⁴θ / (8 n³): the differences fall faster than
    1/n² (the issue's claim), in fact like 1/n³."""
    ns = [3, 6, 12, 24, 48]
    rel = [approximate.largest_relative_differences(n) for n in ns]
    for key in "sva":
        for (n1, d1), (n2, d2) in zip(zip(ns, rel), zip(ns[1:], rel[1:])):
            ratio = d1[key] / d2[key]
            assert ratio > (n2 / n1) ** 2          # faster than 1/n²
        # n³ × error tends to a constant (the coefficient of the next term)
        c = [d[key] * n ** 3 for n, d in zip(ns, rel)]
        assert abs(c[-1] / c[-2] - 1) < 0.05
    # s: r sin⁴θ/(8n³) at 90°, relative to the stroke 2r -> 1/(16 n³)
    assert rel[-1]["s"] * 48 ** 3 == pytest.approx(1 / 16, rel=2e-3)


def test_docs_table_values():
    d = approximate.largest_relative_differences(3)
    assert d["a"] == pytest.approx(0.01517, abs=5e-6)
    assert d["s"] == pytest.approx(0.00245, abs=5e-6)


ROOT = pathlib.Path(__file__).resolve().parents[3]


class _Run:
    def __init__(self, proc):
        self.exit_code, self.stdout, self.output = proc.returncode, proc.stdout, proc.stderr


def _kin(*args):
    return _Run(subprocess.run([sys.executable, "-m", "mechcli", "kin",
                                str(ROOT / "configs/ch1/ex1-2.toml"), "--no-plot", "--json",
                                "-q", *args], capture_output=True, text=True, cwd=ROOT))


def test_cli_json_carries_model_and_differences(tmp_path):
    r = _kin("-o", str(tmp_path), "--set", 'mechanism.model="approximate"')
    assert r.exit_code == 0, r.output
    res = json.loads(r.stdout)["results"]
    assert res["model"] == "approximate"
    assert res["approx_error_a_max_mm_s2"] == pytest.approx(202.2006, abs=1e-3)
    assert res["approx_error_a_max_rel"] == pytest.approx(0.015165, abs=1e-5)
    assert res["approx_error_v_max_rel"] > 0
    assert res["a3_max_mm_s2"] == pytest.approx(7083.3333, abs=1e-3)
    report = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "model: approximate" in report


def test_cli_refuses_offset_and_other_types(tmp_path):
    r = _kin("-o", str(tmp_path), "--set", 'mechanism.model="approximate"',
             "--set", "mechanism.e=5")
    assert r.exit_code == 2
    r = _kin("-o", str(tmp_path), "--set", 'mechanism.model="approximate"',
             "--set", "mechanism.l2=90")
    assert r.exit_code == 2


def test_exact_default_has_no_model_keys(tmp_path):
    r = _kin("-o", str(tmp_path))
    assert r.exit_code == 0
    assert "approx_error_a_max_rel" not in json.loads(r.stdout)["results"]


def test_force_takes_the_approximate_model_and_flywheel_refuses_it(tmp_path):
    """force builds the piston's inertia force on the series (docs/approximate.md; its
    numbers are tested in tests/unit/linkage/test_engine_loads.py); flywheel moves the exact linkage
    and refuses the key (exit 2 naming it), never silently ignoring it."""
    from tests.conftest import one_line_error, run_inprocess
    base = (ROOT / "configs" / "ch2" / "ex2-2.toml").read_text(encoding="utf-8")
    assert 'type = "slider_crank"' in base       # 例 2-2 is the slider-crank preset
    spec = tmp_path / "f.toml"
    spec.write_text(base.replace('type = "slider_crank"',
                                 'type = "slider_crank"\nmodel = "approximate"', 1),
                    encoding="utf-8")
    proc = run_inprocess("force", spec, "--out", tmp_path / "o", "--no-plot", "--json")
    assert proc.returncode == 0, proc.stderr
    res = json.loads(proc.stdout)["results"]
    assert res["model"] == "approximate" and res["approx_error_Mb_max_N_m"] > 0
    from mechcli.spec.errors import SpecError
    from mechcli.spec.kin import refuse_approximate
    from mechcli.spec.reader import load_spec
    with pytest.raises(SpecError, match="model"):
        refuse_approximate(load_spec(spec), "flywheel")
    # with an offset the series does not apply: exit 2 naming the key
    spec.write_text(base.replace('type = "slider_crank"',
                                 'type = "slider_crank"\nmodel = "approximate"', 1)
                    .replace("e = 0", "e = 5"), encoding="utf-8")
    proc = run_inprocess("force", spec, "--out", tmp_path / "p", "--no-plot", "-q")
    assert proc.returncode == 2 and "e" in one_line_error(proc)
