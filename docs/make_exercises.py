#!/usr/bin/env python3
"""Write docs/exercises.md: the book as an index of configs.

Every worked example (【例】) and exercise (习题) of chapters 1-7, as listed in
``docs/book-index.toml`` (its number and what it asks), joined with the configs that
solve it: ``configs/**/ex<N>-<M>[-variant].toml`` for 【例 N-M】 and
``configs/**/exercise<N>-<M>[-variant].toml`` for 习题 N-M.  For each config the row
gives its command, the ``[expected]`` keys that `mechcli check` compares, and where
those values come from:

* a ``# EXPECTED-SOURCE: ...`` comment line in the config, when it has one;
* otherwise what its comments (or description) name: the book's printed values, a
  reference (``tests/reference/<file>.py``), a test that checks it independently
  (``tests/unit/<core package>/test_<name>.py``), a hand derivation ("hand calculation", "by hand",
  "closed form", ...); a 【例】 that names none of them: the book's printed results.

    python docs/make_exercises.py          # rewrite docs/exercises.md
    python docs/make_exercises.py --check  # exit 1 if docs/exercises.md is stale

``tests/unit/exercises/test_exercises_index.py`` runs the check, so the index can never drift
from ``configs/``.  Standard library only (``tomllib``, ``tomli`` before Python 3.11).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

try:
    import tomllib
except ImportError:      # Python < 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
INDEX = ROOT / "docs" / "book-index.toml"
OUT = ROOT / "docs" / "exercises.md"
CONFIGS = ROOT / "configs"

NAME = re.compile(r"^(ex|exercise)(\d+)-(\d+)(?:-.+)?\.toml$")
MARKER = re.compile(r"^#\s*EXPECTED-SOURCE:\s*(.+?)\s*$", re.M)
REFERENCE = re.compile(r"tests/reference/([A-Za-z0-9_]+\.py)")
TEST = re.compile(r"tests/(?:unit|cli|property)/(?:[a-z]+/)?test_[A-Za-z0-9_]+\.py")
HAND = re.compile(r"hand calculation|hand derivation|by hand|closed form|hand-derived|"
                  r"cosine (?:rule|law)|independent check|independent calculation|"
                  r"independent hand|values are independent", re.I)
BOOK = re.compile(r"as printed|book's printed|printed (?:values|results|numbers|table)|"
                  r"the book's (?:table|values|results|numbers)|book prints \d|"
                  r"表 ?\d-\d", re.I)
NO_ANSWER = re.compile(r"no (?:printed|book) answer|prints no answer|gives no answer|"
                       r"book prints only|no printed answers?", re.I)


def label_of(path: Path) -> str | None:
    """The book label a config's file name names (``ex1-2-approximate.toml`` -> 例 1-2)."""
    m = NAME.match(path.name)
    if not m:
        return None
    return f"{'例' if m.group(1) == 'ex' else '习题'} {int(m.group(2))}-{int(m.group(3))}"


def source_of(label: str, text: str, has_expected: bool) -> str:
    """Where a config's [expected] values come from, in a few words."""
    if not has_expected:
        return "—"
    marker = MARKER.search(text)
    if marker:
        return marker.group(1)
    parts = []
    if BOOK.search(text) and not NO_ANSWER.search(text):
        parts.append("the book's printed results")
    refs = sorted(set(REFERENCE.findall(text)))
    if refs:
        parts.append("independent reference " + ", ".join(f"`tests/reference/{r}`" for r in refs))
    tests = sorted(set(TEST.findall(text)))
    if tests:
        parts.append("independent check in " + ", ".join(f"`{t}`" for t in tests))
    if HAND.search(text):
        parts.append("hand derivation in the config's comments")
    if not parts and label.startswith("例") and not NO_ANSWER.search(text):
        parts.append("the book's printed results")
    return "; ".join(parts) if parts else "not stated"


def expected_keys(data: dict) -> list[str]:
    exp = data.get("expected", {})
    return list(exp) if isinstance(exp, dict) else []


def _keys_cell(keys: list[str], limit: int = 4) -> str:
    if not keys:
        return "— (runs only)"
    shown = ", ".join(f"`{k}`" for k in keys[:limit])
    return shown + (f" + {len(keys) - limit} more" if len(keys) > limit else "")


def configs_by_label(configs: Path = CONFIGS) -> dict[str, list[dict]]:
    rows: dict[str, list[dict]] = {}
    for path in sorted(configs.rglob("*.toml")):
        label = label_of(path)
        if label is None:
            continue
        text = path.read_text(encoding="utf-8")
        data = tomllib.loads(text)
        keys = expected_keys(data)
        rows.setdefault(label, []).append({
            "path": path.relative_to(configs.parent).as_posix(),
            "command": data.get("command", "?"),
            "keys": keys,
            "source": source_of(label, text, bool(keys)),
        })
    return rows


def _chapter(label: str) -> int:
    return int(label.split()[1].split("-")[0])


def render(index_path: Path = INDEX, configs: Path = CONFIGS) -> str:
    index = tomllib.loads(index_path.read_text(encoding="utf-8"))["item"]
    by_label = configs_by_label(configs)
    known = {item["label"] for item in index}
    stray = sorted(set(by_label) - known)
    if stray:
        raise SystemExit(f"{index_path}: configs name items the index lacks: {', '.join(stray)}")

    n_ex = sum(1 for i in index if i["label"].startswith("习题"))
    n_ex_done = sum(1 for i in index if i["label"].startswith("习题") and i["label"] in by_label)
    n_wk = len(index) - n_ex
    n_wk_done = sum(1 for i in index if i["label"].startswith("例") and i["label"] in by_label)
    out = [
        "# The book as an index: every 【例】 and 习题",
        "",
        "<!-- generated by docs/make_exercises.py from docs/book-index.toml and configs/;"
        " do not edit -->",
        "",
        "Start here from an assignment: find the example or exercise, run its config with the",
        "command shown (`mechcli COMMAND CONFIG`), and compare with the values `[expected]` checks",
        "(`mechcli check CONFIG`). A config named `…-variant.toml` solves the same problem another",
        "way or checks one case of it. Where the book's figure is lost, the config says how it was",
        "read (`# FIGURE-READING:` comments).",
        "",
        f"Worked examples with a config: {n_wk_done} of {n_wk}; exercises: {n_ex_done} of {n_ex}.",
        "",
        "Where the expected values come from: *the book's printed results* (the tolerance from",
        "the printed digits), a *hand derivation* written in the config's comments, or an",
        "*independent reference* in `tests/reference/` (code that does not use mechcli's",
        "engine, checked against the config by a test) — never mechcli's own output.",
    ]
    chapter = None
    for item in index:
        label = item["label"]
        ch = _chapter(label)
        if ch != chapter:
            chapter = ch
            out += ["", f"## Chapter {ch}", "",
                    "| item | asks | config | command | `[expected]` checks | values from | status |",
                    "|---|---|---|---|---|---|---|"]
        rows = by_label.get(label, [])
        if not rows:
            status = "no config: " + item["missing"] if "missing" in item else "no config yet"
            out.append(f"| {label} | {item['asks']} | — | — | — | — | {status} |")
            continue
        for k, row in enumerate(rows):
            status = (f"checked ({len(row['keys'])} value{'s' if len(row['keys']) != 1 else ''})"
                      if row["keys"] else "runs")
            out.append(f"| {label if k == 0 else ''} | {item['asks'] if k == 0 else ''} | "
                       f"[`{row['path']}`](../{row['path']}) | `{row['command']}` | "
                       f"{_keys_cell(row['keys'])} | {row['source']} | {status} |")
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    text = render()
    if "--check" in argv:
        if not OUT.exists() or OUT.read_text(encoding="utf-8") != text:
            print(f"{OUT} is stale: run python docs/make_exercises.py", file=sys.stderr)
            return 1
        return 0
    OUT.write_text(text, encoding="utf-8")
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
