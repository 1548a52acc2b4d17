"""Chinese renders (issue 18, item 1): with a CJK font every Chinese label is drawn from
it, glyph by glyph after DejaVu Sans, and matplotlib warns of no missing glyph; without
one, titles keep the spec's stem and their English part, and the run says so once."""

import json
import sys
import warnings

import pytest

from tests.conftest import CONFIGS, run_inprocess

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"


@pytest.fixture
def cjk_font():
    """The CJK font mechcli draws with: the ``cjk`` extra's, which the test extra installs
    (``pip install -e '.[test]'``), else the system's.  Without one the test fails (an
    incomplete test install), never skips -- except on Python 3.9, where the extra's font
    package cannot be installed (it needs Python >= 3.10)."""
    from matplotlib import font_manager

    from mechcli.report import plotting

    family = plotting.cjk_font()
    if family is None:
        if sys.version_info < (3, 10):
            pytest.skip("no CJK font on this machine, and the cjk extra needs Python >= 3.10")
        pytest.fail("no CJK font: neither the cjk extra's (pip install -e '.[test]') nor "
                    "one installed on this machine")
    # a family matplotlib knows, whose font draws a CJK character
    entry = next(f for f in font_manager.fontManager.ttflist if f.name == family)
    from matplotlib.ft2font import FT2Font
    assert FT2Font(entry.fname).get_char_index(ord("例")) > 0
    return family


def test_a_zh_figure_draws_every_glyph(cjk_font):
    """Rendering Chinese, Greek and ASCII in one figure raises no "Glyph missing"
    warning (an error here, under filterwarnings = error, even without the filter)."""
    from mechcli.report import plotting

    assert plotting.setup("zh") == "zh"
    assert list(plotting.plt.rcParams["font.family"]) == ["DejaVu Sans", cjk_font]
    fig, ax = plotting.plt.subplots()
    ax.set_title("例 1-1 铰链四杆机构 (four-bar linkage)")
    ax.set_xlabel("曲柄转角 θ1 / °")
    ax.set_ylabel("角速度 ω3 / rad/s")
    ax.plot([0, 1], [0, 1], label="连杆点 F 轨迹")
    ax.legend()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fig.canvas.draw()
    plotting.plt.close(fig)
    glyphs = [str(w.message) for w in caught if "Glyph" in str(w.message)]
    assert glyphs == []
    assert plotting.text("例 1-1 铰链四杆机构") == "例 1-1 铰链四杆机构"


@pytest.mark.parametrize("lang", ["zh", "en"])
def test_a_zh_run_with_a_cjk_font_warns_of_nothing(tmp_path, cjk_font, lang):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        proc = run_inprocess("kin", EX1_1, "--lang", lang, "--json", "--no-animate",
                             "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["warnings"] == []
    assert [str(w.message) for w in caught] == []
    assert (tmp_path / "kin.png").stat().st_size > 10_000


@pytest.fixture
def no_cjk_font(monkeypatch):
    from mechcli.report import plotting
    monkeypatch.setattr(plotting, "cjk_font", lambda: None)


@pytest.mark.parametrize("lang, says", [
    ("en", "figure titles without their Chinese"),
    ("zh", "figure labels in English, titles without their Chinese"),
])
def test_without_a_cjk_font_one_warning_and_no_glyph_flood(tmp_path, no_cjk_font, lang, says):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        proc = run_inprocess("kin", EX1_1, "--lang", lang, "--json", "--animate",
                             "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    cjk = [w for w in doc["warnings"] if "CJK" in w]
    assert cjk == [f"no CJK font found: {says} (pip install 'mechcli[cjk]')"]
    assert [str(w.message) for w in caught] == []
    assert (tmp_path / "kin.gif").is_file()


def test_without_a_cjk_font_the_warning_goes_to_stderr_once(tmp_path, no_cjk_font):
    proc = run_inprocess("kin", EX1_1, "--animate", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert [ln for ln in lines if "CJK" in ln] == [
        f"mechcli: warning: {EX1_1}: no CJK font found: figure titles without their Chinese "
        "(pip install 'mechcli[cjk]')"]
    assert "Glyph" not in proc.stderr


def test_without_a_cjk_font_q_silences_the_warning(tmp_path, no_cjk_font):
    proc = run_inprocess("kin", EX1_1, "-q", "--animate", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "CJK" not in proc.stderr and "Glyph" not in proc.stderr


@pytest.mark.parametrize("title, stem, shown", [
    ("例 1-1 铰链四杆机构 (four-bar linkage)", "ex1-1", "ex1-1: four-bar linkage"),
    ("习题 1-2 铰链四杆机构连杆点 F (coupler point)", "exercise1-2", "exercise1-2: F (coupler point)"),
    ("习题 3-1 铰链四杆机构: l1 = 28, l2 = 52 (杆 4 机架, AB 原动件)", "exercise3-1",
     "exercise3-1: l1 = 28, l2 = 52 (4, AB)"),
    ("【例 5-3】 standard spur gear z = 35 (图 5-7)", "ex5-3", "ex5-3: standard spur gear z = 35 (5-7)"),
    ("回转导杆机构", "rotating", "rotating"),
    ("例 3-1 铰链四杆机构类型判断 (1): 100、150、170、110", "ex3-1", "ex3-1: (1): 100 150 170 110"),
])
def test_title_without_cjk_keeps_the_stem_and_the_english(title, stem, shown):
    from mechcli.report import plotting
    assert plotting.title_without_cjk(title, stem) == shown


def test_text_without_a_font_uses_the_runs_stem(no_cjk_font):
    from mechcli.report import plotting, run
    run.begin("ex1-1")
    assert plotting.text("例 1-1 铰链四杆机构 (four-bar linkage)") == "ex1-1: four-bar linkage"
    assert plotting.text("load '重物W' acts") == "load 'W' acts"   # a label keeps its shape
    assert plotting.text("crank angle θ1 / °") == "crank angle θ1 / °"
    run.begin(None)


@pytest.mark.parametrize("command, spec", [("kin", EX1_1), ("force", CONFIGS / "ch2" / "ex2-4.toml")])
def test_chinese_beside_a_math_symbol_is_drawn_from_the_cjk_font(tmp_path, cjk_font, caplog,
                                                                 command, spec):
    """``曲柄转角 $\\theta_1$ / °``: mathtext draws a string holding a ``$…$`` whole, from
    fonts without CJK glyphs, and logs (not warns) "Font 'default' does not have a glyph"
    for each Chinese character; such texts are drawn in plain Unicode (曲柄转角 θ₁ / °)."""
    import logging

    caplog.set_level(logging.WARNING, logger="matplotlib")
    proc = run_inprocess(command, spec, "--lang", "zh", "-q", "--animate", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert [r.getMessage() for r in caplog.records if "glyph" in r.getMessage()] == []


def test_plain_math_writes_the_books_symbols_in_unicode():
    from mechcli.report import plotting
    cases = {"theta1": "θ₁", "omega3": "ω₃", "FR16": "FR₁₆", "alpha2": "α₂", "Je": "Jₑ"}
    for name, plain in cases.items():
        assert plotting.plain_math(f"曲柄 {plotting.symbol(name)} / °") == f"曲柄 {plain} / °"
    assert plotting.plain_math(r"$dJ_e/d\varphi$ / (kg·m²/rad)") == "dJₑ/dφ / (kg·m²/rad)"
    assert plotting.plain_math("no math, 50$") == "no math, 50$"


#: a spec of every command that titles its figures with the spec's title (例 N-M …)
TITLED = [("kin", "ch1/ex1-1"), ("force", "ch2/ex2-4"), ("cam", "ch4/ex4-2"),
          ("synth", "ch3/ex3-4"), ("flywheel", "ch6/ex6-2"), ("optimize", "ch7/ex7-1")]


def _titles(monkeypatch, tmp_path, command, spec):
    import matplotlib.axes
    import matplotlib.figure

    seen = []
    for cls, name in ((matplotlib.axes.Axes, "set_title"),
                      (matplotlib.figure.FigureBase, "suptitle")):
        original = getattr(cls, name)

        def record(self, label, *args, _original=original, **kw):
            seen.append(str(label))
            return _original(self, label, *args, **kw)

        monkeypatch.setattr(cls, name, record)
    proc = run_inprocess(command, CONFIGS / f"{spec}.toml", "-q", "--no-animate",
                         "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    return seen


@pytest.mark.parametrize("command, spec", TITLED, ids=[s for _, s in TITLED])
def test_figure_titles_label_the_example_as_the_reports_do(tmp_path, monkeypatch, cjk_font,
                                                           command, spec):
    """With a CJK font a figure titled by its spec shows the book's label in the book's
    brackets, 【例 N-M】, as report.txt and the terminal do (before: a bare 例 N-M)."""
    titles = _titles(monkeypatch, tmp_path, command, spec)
    chapter, number = spec.split("/")[1][2:].split("-")[:2]
    label = f"【例 {chapter}-{number}】"
    assert any(label in t for t in titles), titles
    assert not any("例" in t and label not in t for t in titles), titles


def test_figure_titles_without_a_cjk_font_keep_the_stem(tmp_path, monkeypatch):
    """Without a CJK font the label (and the Chinese) is left out and the spec's stem
    names the example: ``ex1-1: four-bar linkage``."""
    from mechcli.report import plotting

    monkeypatch.setattr(plotting, "cjk_font", lambda: None)
    titles = _titles(monkeypatch, tmp_path, "kin", "ch1/ex1-1")
    assert titles and all("例" not in t and "【" not in t for t in titles), titles
    assert any(t.startswith("ex1-1: four-bar linkage") for t in titles), titles
