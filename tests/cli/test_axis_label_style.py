"""One style of axis label in every command's figures (issue 18, items 6 and 8): the
quantity, a spaced slash, the unit -- ``x / mm``, ``crank angle θ1 / °``, a compound
unit in parentheses ``ω3 / (rad/s)`` -- in English and in Chinese (before: gear's
``x (mm)``, grashof's ``x/(mm)``, cam's ``s (mm)``, synth's bare ``mm``)."""

import pytest

from mechcli.report import plotting
from tests.conftest import CONFIGS, run_inprocess

#: a config of every command and every kind of figure it draws
RUNS = [("kin", "ch1/ex1-1"), ("kin", "ch1/ex1-3"), ("force", "ch2/ex2-4"),
        ("force", "ch2/engine-steam-horizontal"), ("cam", "ch4/ex4-2"),
        ("cam", "ch4/exercise4-3"), ("gear", "ch5/ex5-1"), ("gear", "ch5/ex5-3"),
        ("gear", "ch5/ex5-4"), ("gear", "ch5/gear-cut"), ("grashof", "ch3/exercise3-1"),
        ("synth", "ch3/ex3-4"), ("synth", "ch3/ex3-6"),
        ("synth", "ch3/burmester-four-poses"), ("flywheel", "ch6/ex6-2"),
        ("flywheel", "ch6/ex6-4"), ("optimize", "ch7/ex7-1"), ("optimize", "ch7/ex7-2-golden"),
        ("synth", "atlas/page-seed-example")]

#: labels with no unit by nature: a count, a ratio, a dimensionless coordinate
UNITLESS = {"iteration", "迭代次数", "record", "记录", "period-map evaluation", "x", "error in y",
            "y 的误差", "objective f", "目标函数 f", "constraint violation", "约束违反量",
            "B (follower / crank)", "C (frame / crank)", "B (摇杆 / 曲柄)", "C (机架 / 曲柄)",
            "x / crank", "y / crank", "dψ/dδ", "类角速度 dψ/dδ", "dψ/dδ  (- -)"}


@pytest.mark.parametrize("lang", ["en", "zh"])
@pytest.mark.parametrize("command, spec", RUNS, ids=[s for _, s in RUNS])
def test_every_axis_label_reads_quantity_slash_unit(tmp_path, monkeypatch, command, spec,
                                                    lang):
    import matplotlib.axes

    seen = []
    for name in ("set_xlabel", "set_ylabel"):
        original = getattr(matplotlib.axes.Axes, name)

        def record(self, label, *args, _original=original, **kw):
            seen.append(str(label))
            return _original(self, label, *args, **kw)

        monkeypatch.setattr(matplotlib.axes.Axes, name, record)
    proc = run_inprocess(command, CONFIGS / f"{spec}.toml", "-q", "--no-animate",
                         "--lang", lang, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    labels = [s for s in seen if s]
    assert labels, "no figure drawn"
    bad = [s for s in labels if not plotting.AXIS_LABEL.match(s) and s not in UNITLESS]
    assert not bad


def test_axis_label_puts_a_compound_unit_in_parentheses():
    assert plotting.axis_label("x", "mm") == "x / mm"
    assert plotting.axis_label("crank angle θ1", "°") == "crank angle θ1 / °"
    assert plotting.axis_label("ω3", "rad/s") == "ω3 / (rad/s)"
    assert plotting.axis_label("Mb", "N·m") == "Mb / N·m"
    assert plotting.axis_label("K", "") == "K" and plotting.axis_label("i", "1") == "i"
    for good in ("x / mm", "ω3 / (rad/s)", "曲柄转角 θ1 / °", "ds/dδ / (mm/rad)",
                 "$J_e$ / kg·m²  (—)"):
        assert plotting.AXIS_LABEL.match(good), good
    for old in ("x (mm)", "x/(mm)", "θ1/(°)", "ω3 / rad/s", "mm", "x [mm]"):
        assert not plotting.AXIS_LABEL.match(old), old
