"""``docs/own-problem.md`` works as written: its spec blocks are written to the files it
names and its commands are run in that order, in-process, in a fresh folder (issue 31 §3).

The specs' ``[expected]`` values are hand calculations written in the page (the
slider-crank's limit positions, the cam laws' peak derivatives, the gear pair's closed
forms), so ``mechcli check`` passing on them is the check of the page's numbers, and the
page's deliberate slip must make it exit 4.
"""

import re
import shlex
import sys

from tests.conftest import ROOT, run_inprocess

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

DOC = ROOT / "docs" / "own-problem.md"


def steps(text):
    """The page's blocks in order: ``("file", name, text)`` for a ```toml block (named by
    the last ``*.toml`` in backticks before it) and ``("run", argv, exit code)`` for each
    ``mechcli`` line of a ```sh block (``# exits N`` at its end: the code it must give)."""
    out = []
    for m in re.finditer(r"```(toml|sh)\n(.*?)```", text, re.S):
        if m.group(1) == "toml":
            named = re.findall(r"`([\w.-]+\.toml)`", text[:m.start()])
            out.append(("file", named[-1], m.group(2)))
            continue
        for line in m.group(2).splitlines():
            if not line.startswith("mechcli "):
                continue
            code = re.search(r"#\s*exits (\d+)\s*$", line)
            argv = shlex.split(line.split("#")[0])[1:]
            out.append(("run", argv, int(code.group(1)) if code else 0))
    return out


def test_the_page_runs_as_written(tmp_path, monkeypatch):
    text = DOC.read_text(encoding="utf-8")
    todo = steps(text)
    specs = [s for s in todo if s[0] == "file"]
    runs = [s for s in todo if s[0] == "run"]
    # one linkage, one cam, one gear pair, each written, run and checked
    assert [tomllib.loads(t)["command"] for _, _, t in specs] == ["kin", "cam", "gear"]
    assert {a[0] for _, a, _ in runs} >= {"new", "kin", "cam", "gear", "check"}
    monkeypatch.chdir(tmp_path)
    for kind, what, extra in todo:
        if kind == "file":
            (tmp_path / what).write_text(extra, encoding="utf-8")
            continue
        proc = run_inprocess(*what)
        assert proc.returncode == extra, (what, proc.stdout[-2000:], proc.stderr)
    # the hand-worked values are there and were compared: 3 + 4 + 6
    assert sum(len(tomllib.loads(t).get("expected", {})) for _, _, t in specs) == 13
    # the files the page says to hand in
    for name in ("slider/report.txt", "slider/kin.csv", "slider/kin.png", "slider/outputs.json",
                 "cam/profile.png", "cam/motion.png", "pair/pair.png"):
        assert (tmp_path / "out" / name).is_file(), name


def test_the_page_is_linked_from_the_readme():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "(docs/own-problem.md)" in readme
