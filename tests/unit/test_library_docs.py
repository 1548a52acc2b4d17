"""Every ```python block of docs/library.md runs as written (issue 33 §3).

The blocks run in file order in one namespace (a section uses the names of the sections
before it), section by section; a failure names the line of docs/library.md it happened
on.  A block that uses pandas (``to_frame``) is left out where pandas is not installed
(the rest of its section runs, then the section is reported as skipped).
The blocks assert their numbers themselves (the book's values, closed forms).
"""

import importlib.util
import re
import traceback

import pytest

from tests.conftest import ROOT

DOC = ROOT / "docs" / "library.md"
NAME = "docs/library.md"


def _sections():
    """``[(heading, [(first line of the code, code)])]`` of the sections holding code."""
    sections, heading = [], "(top)"
    lines = DOC.read_text(encoding="utf-8").split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("## "):
            heading = line[3:].strip()
        elif line.strip() == "```python":
            j = next(k for k in range(i + 1, len(lines)) if lines[k].strip() == "```")
            if not sections or sections[-1][0] != heading:
                sections.append((heading, []))
            sections[-1][1].append((i + 2, "\n".join(lines[i + 1:j]) + "\n"))
            i = j
        i += 1
    return sections


SECTIONS = _sections()


def _needs_pandas(code):
    return re.search(r"\bto_frame\b|\bpandas\b", code) is not None


def _run(blocks, ns):
    """Run *blocks* in *ns*; returns the first lines of those left out because they need
    pandas and it is not installed (they define nothing a later block uses)."""
    have_pandas = importlib.util.find_spec("pandas") is not None
    left_out = []
    for first, code in blocks:
        if _needs_pandas(code) and not have_pandas:
            left_out.append(first)
            continue
        # padded so that line numbers in a traceback are the file's
        compiled = compile("\n" * (first - 1) + code, NAME, "exec")
        try:
            exec(compiled, ns)  # noqa: S102
        except Exception as exc:  # noqa: BLE001 -- any failure, named by its line
            lines = [f.lineno for f in traceback.extract_tb(exc.__traceback__)
                     if f.filename == NAME]
            where = lines[-1] if lines else first
            pytest.fail(f"{NAME}:{where}: the block starting at line {first} fails: "
                        f"{type(exc).__name__}: {exc}", pytrace=False)
    return left_out


@pytest.fixture(scope="module")
def namespace():
    return {"ns": {"__name__": "library_md"}, "done": {}}


@pytest.mark.parametrize("index", range(len(SECTIONS)), ids=[h for h, _ in SECTIONS])
def test_section_runs(index, namespace, monkeypatch):
    monkeypatch.chdir(ROOT)   # the blocks name configs/ relative to the repository's root
    for k in range(index + 1):   # the sections before it first, if they have not run
        if k not in namespace["done"]:
            namespace["done"][k] = _run(SECTIONS[k][1], namespace["ns"])
    left_out = namespace["done"][index]
    if left_out:
        pytest.importorskip("pandas", reason=f"the blocks of {NAME} at lines {left_out} "
                                             "use pandas; the others ran")


def test_every_block_is_found():
    """The extraction sees every fence of the file (a block it missed would go untested)."""
    text = DOC.read_text(encoding="utf-8")
    found = sum(len(blocks) for _, blocks in SECTIONS)
    assert found == text.count("```python\n") and found >= 7


def test_a_failing_block_is_reported_with_its_line():
    """The runner itself: an error in a block fails with the line it is on."""
    blocks = [(10, "x = 1\n"), (20, "y = 2\nassert x == 2, 'no'\n")]
    with pytest.raises(pytest.fail.Exception, match=rf"{NAME}:21: the block starting at "
                                                     r"line 20 fails: AssertionError: no"):
        _run(blocks, {})
