"""The public library API: lazy top-level names, presets in the core, batched solves."""

import re
import subprocess
import sys

import numpy as np
import pytest

from tests.conftest import ROOT


def test_docs_library_examples_run(capsys):
    """Every python block of docs/library.md runs, in order, in one namespace; the
    blocks assert the book's 例 1-1 swing (70.1745°) themselves."""
    text = (ROOT / "docs" / "library.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 3
    ns = {}
    for block in blocks:
        exec(compile(block, "docs/library.md", "exec"), ns)  # noqa: S102
    out = capsys.readouterr().out
    assert out.count("l3 = ") == 5 and "runs: True" in out


def test_top_level_names_are_lazy():
    code = ("import sys, mechcli; a = 'numpy' in sys.modules; mechcli.four_bar;"
            "print(a, 'numpy' in sys.modules, sorted(set(mechcli.__all__) - set(dir(mechcli))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         check=True).stdout.strip().split(maxsplit=2)
    assert out == ["False", "True", "[]"]


def test_unknown_top_level_name_raises():
    import mechcli
    with pytest.raises(AttributeError, match="no attribute 'fourbar'"):
        mechcli.fourbar  # noqa: B018


def _designs(m_designs, seed):
    rng = np.random.default_rng(seed)
    return [rng.uniform(lo, hi, (m_designs, 1))
            for lo, hi in ((0.08, 0.11), (0.24, 0.27), (0.17, 0.19), (0.29, 0.31))]


@pytest.mark.parametrize("preset, args", [
    ("four_bar", lambda l1, l2, l3, l4: (l1, l2, l3, l4)),
    ("four_bar", lambda l1, l2, l3, l4: (l1, l2, l3, l4, "crossed")),
    ("slider_crank", lambda l1, l2, l3, l4: (l1, l2 + 0.1, l1 * 0.3)),
    ("guide_bar", lambda l1, l2, l3, l4: (l1, l4, 0.2 * l1)),
    ("guide_bar", lambda l1, l2, l3, l4: (l4, l1)),                 # rotating guide-bar
    ("shaper", lambda l1, l2, l3, l4: (l1, 3 * l3, 2 * l3, l4, 1.7 * l4)),
])
def test_batch_equals_separate_solves(preset, args):
    """M designs in one call give bit for bit what M separate solves give."""
    import mechcli
    build = getattr(mechcli, preset)
    params = args(*_designs(4, 3))
    theta = np.radians(np.arange(0.0, 360.0, 7.5))
    inputs = {1: mechcli.DriverMotion(theta, 10.0, 2.0)}
    batch = mechcli.solve(build(*params), inputs, order=2)
    assert batch.regular.shape == (4, theta.size)
    for k in range(4):
        one = mechcli.solve(build(*[p if np.ndim(p) == 0 or isinstance(p, str) else
                                    float(np.ravel(p)[k]) for p in params]), inputs, order=2)
        np.testing.assert_array_equal(batch.regular[k], one.regular)
        for n, lm in one.links.items():
            for attr in ("theta", "omega", "alpha"):
                np.testing.assert_array_equal(getattr(batch.links[n], attr)[k],
                                              getattr(lm, attr))
        for name, pm in one.points.items():
            np.testing.assert_array_equal(batch.points[name].ax[k], pm.ax)
        for name, sm in one.slides.items():
            np.testing.assert_array_equal(batch.slides[name].a[k], sm.a)


def test_batch_feasibility_per_design():
    """A design that cannot turn its crank (l1 + l4 > l2 + l3: not Grashof) is not
    feasible everywhere; the Grashof designs are."""
    import mechcli
    l1 = np.array([[0.10], [0.10], [0.20]])
    l2, l3, l4 = 0.25, 0.18, np.array([[0.30], [0.31], [0.30]])
    m = mechcli.solve(mechcli.four_bar(l1, l2, l3, l4),
                      {1: mechcli.DriverMotion(np.radians(np.arange(0, 360.0, 1.0)), 1.0)})
    # Grashof: 0.10 + 0.30 <= 0.25 + 0.18 -> crank-rocker; 0.10 + 0.31 <= 0.43 too;
    # 0.20 + 0.30 > 0.43 -> no full turn
    assert m.feasible.all(axis=-1).tolist() == [True, True, False]
    # assembly fails where |BD| > l2 + l3: near theta1 = 180° for the third design
    assert not m.feasible[2, 180] and m.feasible[2, 0]


def test_scale_of_a_batch_is_per_design():
    import mechcli
    lk = mechcli.four_bar(np.array([[0.1], [2.0]]), 0.25, 0.18, 0.3)
    np.testing.assert_array_equal(lk.scale(), [[0.3], [2.0]])
    assert lk.shape == (2, 1)
    assert mechcli.four_bar(0.1, 0.25, 0.18, 0.3).scale() == 0.3


def test_presets_match_the_book_numbering():
    """四杆机构 1 crank, 2 coupler, 3 rocker, 4 frame; the shaper's frame is 6."""
    import mechcli
    fb = mechcli.four_bar(0.1, 0.25, 0.18, 0.3)
    assert fb.frame == 4 and fb.rotating_links == (2, 3) and fb.transmission_joints == ("C",)
    sh = mechcli.shaper(0.1, 0.6, 0.15, 0.38, 0.6)
    assert sh.frame == 6 and sh.slide_names == ("23", "E") and sh.translating_links == (5,)
    assert mechcli.slider_crank(0.1, 0.3).slide_names == ("3",)
    with pytest.raises(ValueError, match="branch"):
        mechcli.four_bar(0.1, 0.25, 0.18, 0.3, branch="opne")
