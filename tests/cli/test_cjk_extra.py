"""Chinese that comes with the install (issue 31 §1): ``pip install 'mechcli[cjk]'``
brings Noto Sans SC (package pylopdf-fonts-zh-cn, SIL OFL 1.1), which a figure run finds
and registers with matplotlib by itself; without any CJK font a run warns once, and
``-q`` silences that warning."""

import ast
import json
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from tests.conftest import CONFIGS, ROOT, run_inprocess

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"
#: three PNGs (force.png, frame.png, hodograph.png) and a GIF in one run
EX2_4 = CONFIGS / "ch2" / "ex2-4.toml"
#: the extra's package (pyproject.toml: [project.optional-dependencies] cjk)
FONT_PACKAGE = "pylopdf_fonts_zh_cn"
WARNING = "no CJK font found: figure labels in English, titles without their Chinese " \
          "(pip install 'mechcli[cjk]')"


@pytest.fixture
def packaged():
    """The path of the cjk extra's font file, which the test extra installs; without it
    the test fails (an incomplete test install), except on Python 3.9, where the font
    package cannot be installed (it needs Python >= 3.10)."""
    from mechcli.report import plotting

    path = plotting.packaged_font()
    if path is None:
        if sys.version_info < (3, 10):
            pytest.skip("the cjk extra's font package needs Python >= 3.10")
        pytest.fail(f"no {FONT_PACKAGE}: pip install -e '.[test]' (or '.[cjk]')")
    return path


def test_the_extra_font_is_found_and_registered_by_itself(packaged):
    import importlib.util

    from matplotlib import font_manager

    from mechcli.report import plotting

    folder = Path(importlib.util.find_spec(FONT_PACKAGE).origin).parent
    assert packaged.parent == folder and packaged.name == "NotoSansSC-Regular.otf"
    # the extra's font comes first, whatever the machine has: figures look alike everywhere
    assert plotting.cjk_font() == "Noto Sans SC"
    names = [f.name for f in font_manager.fontManager.ttflist if f.fname == str(packaged)]
    assert names == ["Noto Sans SC"]   # registered once, however often it is looked up
    assert plotting.cjk_font() == "Noto Sans SC"
    assert [f.fname for f in font_manager.fontManager.ttflist].count(str(packaged)) == 1


def test_a_zh_run_draws_its_chinese_from_the_packaged_font(tmp_path, monkeypatch, caplog,
                                                           packaged):
    import logging

    import matplotlib
    from matplotlib import font_manager
    from matplotlib.backends import backend_agg
    from matplotlib.ft2font import FT2Font

    asked = []   # the font files the Agg renderer opened to draw text

    def get_font(paths, *args, _original=backend_agg.get_font, **kw):
        asked.extend([paths] if isinstance(paths, (str, Path)) else list(paths))
        return _original(paths, *args, **kw)

    monkeypatch.setattr(backend_agg, "get_font", get_font)
    caplog.set_level(logging.WARNING, logger="matplotlib")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        proc = run_inprocess("kin", EX1_1, "--lang", "zh", "--json", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert [w for w in doc["warnings"] if "CJK" in w or "glyph" in w] == []
    assert [str(w.message) for w in caught] == []                 # no "Glyph … missing"
    assert [r.getMessage() for r in caplog.records if "glyph" in r.getMessage()] == []
    assert str(packaged) in {str(p) for p in asked}
    # the font matplotlib resolves for a label: DejaVu Sans has no 曲, the extra's font has
    families = list(matplotlib.rcParams["font.family"])
    assert families == ["DejaVu Sans", "Noto Sans SC"]
    found = font_manager.fontManager._find_fonts_by_props(
        font_manager.FontProperties(family=families))
    assert [Path(p).name for p in found] == ["DejaVuSans.ttf", packaged.name]
    assert FT2Font(str(found[0])).get_char_index(ord("曲")) == 0
    assert FT2Font(str(found[1])).get_char_index(ord("曲")) > 0


def _report_characters():
    """Every non-ASCII character of the report modules' string literals and of the wording
    catalogue (the labels, titles and legends of ``--lang zh``)."""
    import mechcli   # the installed package's modules (CI runs the suite against the wheel)

    chars = set()
    # the report modules and the wording catalogue (mechcli/report/words/*.py), where
    # most labels live
    for path in sorted((Path(mechcli.__file__).parent / "report").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                chars |= {c for c in node.value if ord(c) > 0x7F}
    return chars


def _title_characters():
    """Every non-ASCII character of the shipped specs' titles (drawn over figures)."""
    from mechcli.spec.reader import tomllib

    chars = set()
    for path in sorted(CONFIGS.rglob("*.toml")):
        title = str(tomllib.loads(path.read_text(encoding="utf-8")).get("title", ""))
        chars |= {c for c in title if ord(c) > 0x7F}
    return chars


def test_every_chinese_character_mechcli_draws_is_in_the_packaged_font(packaged):
    """The subset font covers every Chinese character of the zh labels and of the shipped
    specs' titles, and DejaVu Sans or it every other character (Greek, sub- and
    superscripts, symbols): the reference is the fonts' own character maps."""
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    from mechcli.report import plotting

    cjk_font = FT2Font(str(packaged))
    base = FT2Font(font_manager.findfont(plotting._BASE_FAMILY))
    chars = _report_characters() | _title_characters()
    chinese = {c for c in chars if plotting._is_cjk(c)}
    assert len(chinese) > 300   # the collection found the labels (471 characters today)
    assert sorted(c for c in chinese if cjk_font.get_char_index(ord(c)) == 0) == []
    assert sorted(c for c in chars - chinese if cjk_font.get_char_index(ord(c)) == 0
                  and base.get_char_index(ord(c)) == 0) == []


@pytest.fixture
def no_cjk_font(monkeypatch):
    """No CJK font at all: neither the extra's nor one the system has (the lookup finds
    nothing; the font may stay registered with matplotlib under a name no longer asked
    for)."""
    from mechcli.report import plotting

    monkeypatch.setattr(plotting, "packaged_font", lambda: None)
    monkeypatch.setattr(plotting, "_CJK_FAMILIES", ())
    monkeypatch.setattr(plotting, "_found", (None, None))


def _cjk_lines(stderr):
    return [ln for ln in stderr.splitlines() if "CJK" in ln or "Glyph" in ln]


def test_without_a_cjk_font_one_short_warning_per_run(tmp_path, no_cjk_font):
    """Four pictures (three PNGs and a GIF), two runs in one process: one warning each."""
    for _ in range(2):
        proc = run_inprocess("force", EX2_4, "--lang", "zh", "--animate", "-o", tmp_path)
        assert proc.returncode == 0, proc.stderr
        assert len(list(tmp_path.glob("*.png"))) == 3 and (tmp_path / "force.gif").is_file()
        assert _cjk_lines(proc.stderr) == [f"mechcli: warning: {EX2_4}: {WARNING}"]


def test_without_a_cjk_font_q_silences_the_warning_and_json_keeps_it(tmp_path, no_cjk_font):
    proc = run_inprocess("force", EX2_4, "--lang", "zh", "-q", "--animate", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert _cjk_lines(proc.stderr) == []
    proc = run_inprocess("force", EX2_4, "--lang", "zh", "-q", "--json", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert [w for w in json.loads(proc.stdout)["warnings"] if "CJK" in w] == [WARNING]


def _imported_after(args):
    """Whether matplotlib and the extra's font package were imported by ``mechcli ARGS``
    in a fresh process."""
    code = ("import sys\nfrom mechcli.cli import main\n"
            f"try:\n    main({[str(a) for a in args]!r})\n"
            "except SystemExit as e:\n    assert not e.code, e.code\n"
            f"print('matplotlib' in sys.modules, {FONT_PACKAGE!r} in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout.split()[-2:]


def test_the_font_is_looked_up_only_when_a_figure_is_drawn(tmp_path, packaged):
    assert _imported_after(["kin", EX1_1, "--json", "--no-plot", "-o", tmp_path]) \
        == ["False", "False"]
    assert _imported_after(["kin", EX1_1, "--lang", "zh", "-q", "-o", tmp_path]) \
        == ["True", "True"]


def test_the_extra_is_declared_with_the_fonts_licence():
    """pyproject's cjk extra names the font package (the test extra too, so the tests above
    run), and the README's install line shows the extra with the font's licence."""
    from tests.unit.test_packaging import project_extras

    extras = project_extras()
    font = "pylopdf-fonts-zh-cn>=0.1.1; python_version >= '3.10'"
    assert extras["cjk"] == [font] and font in extras["test"]
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "pip install -e '.[cjk,test]'" in readme and "pip install 'mechcli[cjk]'" in readme
    assert "SIL Open Font License 1.1" in readme
