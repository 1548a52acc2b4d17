"""习题 1-15's isosceles slider-crank (r = l): a sweep across its change points is a
clear exit 2 naming them, not numbers from whichever mode the branch formula takes."""

from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec

SPEC = (CONFIGS / "ch1" / "exercise1-15.toml").read_text(encoding="utf-8").split("[expected]")[0]


def test_a_sweep_across_the_change_points_is_exit_3(tmp_path):
    # r = l: the slider reaches the crank pivot at θ1 = ±90° (by hand: s3 = 2r cos θ1 = 0)
    text = SPEC.replace("start = -80", "start = 0").replace("stop = 80", "stop = 360")
    proc = run_inprocess("kin", write_spec(tmp_path, text), "--out", tmp_path / "o")
    assert proc.returncode == 3
    msg = one_line_error(proc)
    assert "dead points at θ1 = 90°, 270°" in msg and "partial" in msg


def test_a_partial_sweep_reports_no_roots_in_round_off(tmp_path):
    # with partial = true the sweep goes on past θ1 = 90° on the branch where the slider
    # rests at the crank pivot (s3 = 0, a3 = 0 to round-off) until 270°: a3's zeros there
    # were ~200 sign changes of noise; none is reported inside that stretch now
    import json

    text = SPEC.replace("start = -80", "start = 0").replace("stop = 80", "stop = 360")
    text = text.replace("[input]\n", "[input]\npartial = true\n")
    proc = run_inprocess("kin", write_spec(tmp_path, text), "--out", tmp_path / "o",
                         "--json", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    zeros = json.loads(proc.stdout)["results"]["a3_zero_at_deg"]
    assert len(zeros) <= 4, zeros
    assert not [z for z in zeros if 95 < z < 265], zeros
