"""A quantity that is zero in truth computes as round-off: kin says so, not "0 digits".

习题 1-15's isosceles slider-crank (r = l = 100 mm, e = 0, ω1 = 10 rad/s) has, by the hand
derivation in ``configs/ch1/exercise1-15.toml``, θ2 = −θ1, ω2 = −ω1 and α2 = 0 exactly on
its arc: the engine computes α2 as noise of ~1e-12 rad/s².  Counting that noise's digits
against its own peak reported "alpha2 keeps about 0.0 correct significant digits" and the
figure drew the noise as a curve with a 1e-12 axis.  The round-off is measured against the
natural magnitude of an angular acceleration, ω1² + |α1| = 100 rad/s² (hand), times
:data:`~mechcli.core.linkage.accuracy.NOISE_REL` = 1e4 ε ≈ 2.2e-12.
"""

import json
import math

import numpy as np

from mechcli.core.linkage import DriverMotion, slider_crank, solve
from mechcli.core.linkage.accuracy import NOISE_REL, noise_floor
from mechcli.core.linkage.kinematics import Sweep
from mechcli.report import plotting

from tests.conftest import CONFIGS, run_inprocess

W1 = 10.0                                   # rad/s, 习题 1-15
R = 0.1                                     # m, r = l = 100 mm


def _sweep():
    return Sweep(1, np.radians(np.arange(-80.0, 80.5, 1.0)), dq=W1)


def test_noise_floor_is_the_natural_magnitude_times_NOISE_REL():
    q = np.radians(np.arange(-80.0, 80.5, 1.0))
    lk = slider_crank(100.0, 100.0)
    # hand: angle 1 rad, angular velocity |ω1| = 10, angular acceleration ω1² = 100
    assert noise_floor(lk, _sweep(), q, "angle") == NOISE_REL * 1.0
    assert math.isclose(noise_floor(lk, _sweep(), q, "angvel"), NOISE_REL * 10.0, rel_tol=1e-15)
    assert math.isclose(noise_floor(lk, _sweep(), q, "angacc"), NOISE_REL * 100.0, rel_tol=1e-15)
    assert noise_floor(lk, _sweep(), q, "force") is None


def test_alpha2_is_round_off_below_the_floor_and_a3_is_exact():
    lk = slider_crank(R, R)
    th = np.radians(np.arange(-80.0, 80.5, 1.0))
    m = solve(lk, {1: DriverMotion(th, W1, 0.0)}, order=2)
    alpha2 = np.asarray(m.links[2].alpha)
    floor = noise_floor(lk, _sweep(), th, "angacc")
    assert np.max(np.abs(alpha2)) > 0.0            # noise, not an exact zero: the case
    assert np.max(np.abs(alpha2)) <= floor          # ... and below the floor
    # relative to its own magnitude the noise varies wildly: only the floor tells
    assert not plotting.is_constant(alpha2)


def test_the_figure_names_alpha2_as_zero_instead_of_drawing_noise():
    """kin.png's acceleration panel: α2 is named "α2 ≡ 0" in the legend (it was drawn as a
    curve of ±3e-12 with a 1e-12 axis), a3 = −2rω1² cos θ1 is drawn."""
    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities
    from mechcli.report import kin_plots
    from mechcli.spec.kin import load_kin_spec

    spec = load_kin_spec(CONFIGS / "ch1" / "exercise1-15.toml", ())
    sweep = spec.input.sweep()
    qs = default_quantities(spec.linkage, spec.output.order)
    result = analyse_sweep(spec.linkage, sweep, qs, spec.output.order)
    acc = [q for q in qs if q.symbol in ("alpha2", "a3")]
    assert len(acc) == 2
    fig, ax = plotting.subplots()
    kin_plots._plot_group(ax, spec, result, acc, np.degrees(result.q), kin_plots._TITLES["en"])
    legend = [t.get_text() for t in ax.get_legend().texts]
    plotting.close(fig)
    assert any("≡ 0 " in s and "alpha" in s for s in legend), legend
    assert len(ax.lines) == 1                      # a3 alone is drawn


def test_kin_counts_no_digits_of_a_zero_and_warns_not(tmp_path):
    res = run_inprocess("kin", CONFIGS / "ch1" / "exercise1-15.toml", "--json", "-q",
                        "--no-plot", "--out", tmp_path)
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout)
    acc = out["results"]["accuracy"]
    assert "alpha2" not in acc["by_quantity"]      # zero in truth: no digits to count
    assert acc["by_quantity"]["a3"] >= 12          # a3 = −2rω1² cos θ1 (hand) is exact
    assert acc["accelerations"] == acc["by_quantity"]["a3"]
    assert not any("alpha2" in w for w in out["warnings"])


def test_a_constant_quantity_has_its_value_and_no_location(tmp_path):
    """ω2 ≡ −ω1 = −10 rad/s and α2 ≡ 0 (hand, above): the extremes say so, with no input
    angle (the search stopped somewhere in noise: 习题 1-15 reported ω2's max at −76.5°
    and its min at −77°); s3 = 2r cos θ1 keeps its located max at θ1 = 0 (hand)."""
    res = run_inprocess("kin", CONFIGS / "ch1" / "exercise1-15.toml", "--json", "-q",
                        "--no-plot", "--out", tmp_path)
    assert res.returncode == 0, res.stderr
    r = json.loads(res.stdout)["results"]
    assert math.isclose(r["omega2_max_rad_s"], -W1, rel_tol=1e-12)
    assert r["omega2_min_rad_s"] == r["omega2_max_rad_s"]     # one value, the samples' mean
    assert r["alpha2_max_rad_s2"] == 0.0 and r["alpha2_min_rad_s2"] == 0.0
    for sym in ("omega2", "alpha2"):
        assert not any(k.startswith(f"{sym}_") and "_at_" in k for k in r), sym
    assert r["alpha2_max_grid_error_rad_s2"] == 0.0
    assert abs(r["s3_max_at_deg"]) <= r["s3_max_at_deg_tol"] + 1e-9
    assert math.isclose(r["s3_max_mm"], 200.0, rel_tol=1e-12)
    table = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert table.count("constant") == 4          # the ω2 and α2 rows, max and min cells


def test_a_small_real_value_is_not_round_off():
    """A parallelogram four-bar (l1 = l3 = 0.1, l2 = l4 = 0.3 m, open) at ω1 = 100 rad/s and
    α1 = 1e-6 rad/s²: by hand the coupler translates (θ2 ≡ 0: ω2 = α2 = 0) and the rocker
    copies the crank (ω3 ≡ ω1, α3 ≡ α1 = 1e-6).  α3 is 1e-10 of ω1² = 1e4, far above the
    round-off (~1e-12 rad/s² here): constant, but 1e-6, not 0 (a review's probe: with a floor
    of 1e-9 ω1² it read 0)."""
    from mechcli.core.linkage import four_bar
    from mechcli.core.linkage.kinematics import analyse_sweep, default_quantities

    lk = four_bar(0.1, 0.3, 0.1, 0.3)
    # between its change points at 0° and 180°, where α's round-off ~ ε κ³ ω1² grows past 1e-9
    th = np.radians(np.arange(30.0, 150.5, 1.0))
    res = analyse_sweep(lk, Sweep(1, th, 100.0, 1e-6), default_quantities(lk, 2), 2)
    hi, lo = res.extremes["alpha3"]
    assert hi.constant and lo.constant
    # a constant's max and min are one value, its samples' mean: 1e-6 within the round-off
    assert hi.value == lo.value and abs(hi.value - 1e-6) <= 1e-9
    w_hi, _ = res.extremes["omega3"]
    assert w_hi.constant and math.isclose(w_hi.value, 100.0, rel_tol=1e-12)
    a2, _ = res.extremes["alpha2"]
    assert a2.constant and a2.value == 0.0
    assert not res.extremes["theta3"][0].constant      # θ3 = θ1 turns


def test_optimize_rates_no_design_whose_result_lacks_the_key():
    """A term read from another command's results (runner.results.ResultTerms) whose key a
    design's results do not have (the location of a constant quantity's extreme) makes that
    design unrated (ok False), where it raised KeyError (a review's probe)."""
    from mechcli.runner.results import ResultTerms

    terms = ResultTerms.__new__(ResultTerms)
    terms.objective = ("omega2_max_at_deg", 1.0)
    terms.bounds = [("omega2_max_rad_s", None, 50.0)]
    terms.results = lambda x: {"omega2_max_rad_s": 10.0} if x[0] > 0 else \
        {"omega2_max_rad_s": 10.0, "omega2_max_at_deg": 30.0}
    f, g, ok = terms(np.array([[1.0], [-1.0]]))
    assert ok.tolist() == [False, True]
    assert f[1] == 30.0 and g[1, 0] == 10.0 - 50.0
