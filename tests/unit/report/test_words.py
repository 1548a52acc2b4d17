"""The report's wording catalogue (mechcli/report/words): complete in both languages, every key the
report modules look up exists, and no report module words a sentence in an inline language branch
(issue 32 §4)."""
import ast
import re
import string
from pathlib import Path

import pytest

import mechcli.report
from mechcli.report import words

REPORT = Path(mechcli.report.__file__).parent
SECTIONS = sorted(p.stem for p in (REPORT / "words").glob("*.py") if p.stem != "__init__")

#: an inline language branch: `… if zh else …`, `lang == "zh"`, a {"en": …, "zh": …} literal
BRANCH = re.compile(r"""\bif\s+zh\b|\bzh\s+else\b|lang\s*[!=]=\s*["']zh["']|["']zh["']\s*[!=]=\s*lang"""
                    r"""|["']zh["']\s*:\s*[{(\[]""")

#: report modules still carrying inline branches, with how many; this list only shrinks
REMAINING: dict = {}


def _fields(text):
    return sorted({f for _, f, _, _ in string.Formatter().parse(text) if f})


@pytest.mark.parametrize("name", SECTIONS)
def test_every_entry_in_both_languages_with_the_same_fields(name):
    for key, forms in words.section(name).items():
        assert set(forms) == set(words.LANGUAGES), f"{name}.{key}: {sorted(forms)}"
        assert _fields(forms["en"]) == _fields(forms["zh"]), f"{name}.{key}"


def test_say_formats_and_falls_back_to_english():
    assert words.say("zh", "common.positions", n=361) == "共 361 个位置"
    assert words.say("en", "common.positions", n=361) == "361 positions analysed"
    assert words.say("fr", "common.summary") == "Summary"
    assert words.table("zh", "common")["max"] == "最大值"


def _looked_up():
    """Every literal key passed to say(…, "section.key") in the report package."""
    for path in REPORT.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and getattr(node.func, "id", getattr(node.func, "attr", ""))
                    == "say" and len(node.args) >= 2 and isinstance(node.args[1], ast.Constant)):
                yield path.name, node.args[1].value


def test_every_key_looked_up_exists():
    missing = [(f, k) for f, k in _looked_up()
               if k.partition(".")[0] not in SECTIONS
               or k.partition(".")[2] not in words.section(k.partition(".")[0])]
    assert not missing


def test_no_new_inline_language_branches():
    found = {}
    for path in sorted(REPORT.glob("*.py")):
        n = sum(len(BRANCH.findall(line)) for line in path.read_text(encoding="utf-8").splitlines())
        if n:
            found[path.name] = n
    grown = {k: (v, REMAINING.get(k, 0)) for k, v in found.items() if v > REMAINING.get(k, 0)}
    assert not grown, f"inline language branches added (found, allowed): {grown}"
    shrunk = {k: (found.get(k, 0), v) for k, v in REMAINING.items() if found.get(k, 0) < v}
    assert not shrunk, f"fewer branches than REMAINING says: lower it (found, listed): {shrunk}"
