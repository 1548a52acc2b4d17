"""Nothing a spec contains crashes mechcli, writes outside ``--out`` or corrupts a CSV.

A mutation fuzzer over every config in ``configs/`` (issue 21, item 12 and "Done when").
Each example takes one config, applies one to three mutations drawn from :data:`FAMILIES`
(delete a key or a table, change a value's type, replace a value by an extreme number, an
empty, very long or hostile string, duplicate an item of an array of tables, misspell a key,
add an unknown key, nest a value deeply), writes the mutated TOML with the small writer below
(everything as inline values at the top level, so the rest of the file reads back unchanged)
and runs it in-process with ``--no-plot --no-animate --quiet --out OUT`` (and ``--json`` in
some examples). The contract it asserts on every run:

* the exit code is 0, 2 or 3 (never 1, the "this is a bug" code);
* exit 2 or 3: exactly one stderr line, ``mechcli: error: ...``, and no traceback; with
  ``--json``, stdout is the JSON error object ``{"command", "error", "exit_code"}``;
* exit 0: every CSV under OUT parses with :mod:`csv`, every row has the header's number of
  fields, and no cell is ``nan``/``inf``; with ``--json``, stdout is strict JSON (no NaN);
* nothing is written outside OUT: the sandbox (the working directory, the spec's folder and
  three folders above OUT) is the same, file for file, before and after the run.

Environment knobs for a long local run (the CI default is small and deterministic)::

    FUZZ_EXAMPLES=3000   number of examples (default: ``CI_EXAMPLES``)
    FUZZ_LOG=file.jsonl  record every contract violation there and keep going, instead of
                         failing on (and shrinking) the first one
    FUZZ_SLOW=1          also draw the mutations skipped by default because an unchecked
                         range makes them pathologically slow or large (issue 21 items 6, 11)
    FUZZ_PLOTS=1         let one example in ten write PNG plots (always when a ``name`` changed)
    FUZZ_TIMEOUT=60      seconds before one run counts as hung (default 60)
"""

import contextlib
import copy
import csv
import json
import math
import os
import re
import signal
import sys
import tempfile
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st

from tests.conftest import CONFIGS, run_inprocess
from tests.tomlwrite import Nested, to_toml

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

CONFIG_FILES = sorted(CONFIGS.rglob("*.toml"))
CONFIG_IDS = [str(p.relative_to(CONFIGS)) for p in CONFIG_FILES]

#: the CI default, in examples per config (most runs take 2-20 ms, a few 0.3 s)
CI_PER_CONFIG = 6
#: configs whose one run takes seconds (an atlas built and searched, a global optimization):
#: only HEAVY_EXAMPLES of their examples run unless FUZZ_SLOW (the CI's 10 minutes), and
#: the harness's own unmutated run skips them (test_configs runs each of them unmutated)
HEAVY = {"atlas/exercise7-3-atlas.toml", "atlas/exercise7-4-atlas.toml",
         "ch7/exercise7-1.toml", "ch7/exercise7-3.toml", "ch7/exercise7-4.toml"}
HEAVY_EXAMPLES = 2
#: FUZZ_EXAMPLES is the total over all configs
EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", CI_PER_CONFIG * len(CONFIG_FILES)))
PER_CONFIG = max(1, -(-EXAMPLES // len(CONFIG_FILES)))
LOG = os.environ.get("FUZZ_LOG")
SLOW = bool(os.environ.get("FUZZ_SLOW"))
PLOTS = bool(os.environ.get("FUZZ_PLOTS"))
TIMEOUT = int(os.environ.get("FUZZ_TIMEOUT", 60))
TRACE = os.environ.get("FUZZ_TRACE")  # a file: one JSON line per example, kept or not

# The TOML writer is tests/tomlwrite.py (tomli_w is not a dependency).


def test_toml_writer_round_trips_every_config_and_the_extremes():
    """The writer is the fuzzer's only way to make a spec: it must read back unchanged."""
    for path in CONFIG_FILES:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(to_toml(doc)) == doc, path
    odd = {"a b": ["", "../x", "a,b", 'q"\\\n\t\x7f\x01', "é中"], "": {"k": [[1], {"x": {}}]},
           "n": [0, -1, 1e-300, 1e300, 5e-324, 2 ** 80, -(2 ** 63)], "b": [True, 1.5]}
    assert tomllib.loads(to_toml(odd)) == odd
    for kind in ("array", "table"):
        nested = Nested({"x": [1, "a"]}, 3, kind)
        assert tomllib.loads(to_toml({"n": nested}))["n"] == nested.plain()
    inf = tomllib.loads(to_toml({"p": math.inf, "m": -math.inf, "n": math.nan}))
    assert inf["p"] == math.inf and inf["m"] == -math.inf and math.isnan(inf["n"])


# ---------------------------------------------------------------------------------------
# Where a mutation can apply: every key of every table, every item of every array
# ---------------------------------------------------------------------------------------


def _walk(node, path=()):
    """Yield ``(path, value)`` for every value under ``node`` (keys and list indices).

    The header (``command``, ``title``, ...) and ``[expected]`` come last: hypothesis draws
    the first items of a list more often, and the problem's own keys are the ones to fuzz.
    """
    found = list(_walk_in_order(node, path))
    return sorted(found, key=lambda item: _late(item[0]))


def _late(path):
    if path[:1] == ("expected",):
        return 2
    return 1 if len(path) == 1 and path[0] in HEADER else 0


HEADER = {"command", "title", "units", "description"}


def _walk_in_order(node, path=()):
    items = node.items() if isinstance(node, dict) else enumerate(node)
    for key, value in items:
        yield path + (key,), value
        if isinstance(value, (dict, list)):
            yield from _walk_in_order(value, path + (key,))


def _get(doc, path):
    for key in path:
        doc = doc[key]
    return doc


def _is_table(value):
    return isinstance(value, dict)


def _is_aot(value):
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _dict_slots(doc):
    """Paths of values that sit under a key of a table (not list items)."""
    return [p for p, _ in _walk(doc) if isinstance(_get(doc, p[:-1]), dict)]


def _number_slots(doc):
    return [p for p, v in _walk(doc) if isinstance(v, (int, float)) and not isinstance(v, bool)]


def _string_slots(doc):
    return [p for p, v in _walk(doc) if isinstance(v, str)]


def _tables(doc):
    return [()] + [p for p, v in _walk(doc) if _is_table(v)]


#: keys that set a number of samples, steps or iterations: a tiny step or a huge bound is a
#: legitimate (and, while ranges are unchecked, dangerous) run, skipped unless FUZZ_SLOW
STEP_KEYS = {"step", "stop", "start", "count", "table_step", "points", "frames", "curve_step",
             "step_deg", "limit_deg", "curve_step_deg", "table_step_deg", "table_from_deg",
             "table_to_deg", "alpha_max_deg", "max_iter", "columns", "digits",
             "dms_seconds_digits", "cutter_teeth", "ratio", "theta", "z", "z1", "z2"}


def _raises_cost(path, value):
    """Would setting ``path`` to ``value`` ask for a huge number of samples or steps?"""
    keys = [k for k in path if isinstance(k, str)]
    if not keys or keys[-1] not in STEP_KEYS:
        return False
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    if not math.isfinite(value):
        return False
    return abs(value) > 1e4 or 0 < abs(value) < 1e-3


# ---------------------------------------------------------------------------------------
# The mutation families
# ---------------------------------------------------------------------------------------

NUMBERS = [0, -1, 1e-300, -1e-300, 1e300, -1e300, math.nan, math.inf, -math.inf,
           2 ** 63 - 1, -(2 ** 63), 10 ** 30, 5e-324, 0.5, 1]
#: a sandbox-absolute name is filled in per example ({abs}); a real / would be written as root
HOSTILE = ["../x", "../../../evil", "{abs}/evil", "a,b", 'a"b', "a b", "x/y", "..", ".", "-",
           "nan", "\u200b", "CON", "é中θ", "a\tb"]
#: line breaks in a string (found by this fuzzer: a spec error echoed them raw, making the
#: one-line error two lines; SpecError.format now escapes them)
HOSTILE += ["a\nb", "a;b\r", "a\u2028b"]
LONG = ["x" * 200, "θ" * 300, "L" * 2000]
OTHER_TYPES = ["x", True, 1, 1.5, [1, 2], {"a": 1}, [], {}]
UNKNOWN_KEY = "zz_fuzz_key"


class Skip(Exception):
    """This mutation does not apply to this document (or is excluded): draw another."""


def m_delete_key(doc, draw):
    slots = [p for p in _dict_slots(doc) if not _is_table(_get(doc, p)) and not _is_aot(_get(doc, p))]
    path = _pick(draw, slots)
    del _get(doc, path[:-1])[path[-1]]
    return f"delete key {_dotted(path)}"


def m_delete_table(doc, draw):
    slots = [p for p, v in _walk(doc) if _is_table(v) or _is_aot(v)]
    path = _pick(draw, slots)
    parent = _get(doc, path[:-1])
    if isinstance(parent, list) and len(parent) == 1:
        path = path[:-1]
        parent = _get(doc, path[:-1])
    del parent[path[-1]]
    return f"delete table {_dotted(path)}"


def m_change_type(doc, draw):
    slots = [p for p, _ in _walk(doc)]
    path = _pick(draw, slots)
    old = _get(doc, path)
    new = draw(st.sampled_from([v for v in OTHER_TYPES if type(v) is not type(old)]))
    _get(doc, path[:-1])[path[-1]] = copy.deepcopy(new)
    return f"type {_dotted(path)}: {old!r:.40} -> {new!r}"


def m_extreme_number(doc, draw):
    slots = _number_slots(doc)
    path = _pick(draw, slots)
    new = draw(st.sampled_from(NUMBERS))
    if not SLOW and _raises_cost(path, new):
        _skip()
    old = _get(doc, path)
    _get(doc, path[:-1])[path[-1]] = new
    return f"number {_dotted(path)}: {old!r} -> {new!r}"


def m_empty_string(doc, draw):
    slots = _string_slots(doc)
    path = _pick(draw, slots)
    _get(doc, path[:-1])[path[-1]] = ""
    return f"empty string {_dotted(path)}"


def m_long_string(doc, draw):
    slots = _string_slots(doc)
    path = _pick(draw, slots)
    new = draw(st.sampled_from(LONG))
    _get(doc, path[:-1])[path[-1]] = new
    return f"long string {_dotted(path)}: {len(new)} x {new[0]!r}"


def m_hostile_name(doc, draw):
    slots = _string_slots(doc)
    path = _pick(draw, slots)
    new = draw(st.sampled_from(HOSTILE))
    _get(doc, path[:-1])[path[-1]] = new
    return f"hostile string {_dotted(path)}: {new!r}"


def m_duplicate_item(doc, draw):
    slots = [p for p, v in _walk(doc) if _is_aot(v)]
    path = _pick(draw, slots)
    items = _get(doc, path)
    i = draw(st.integers(0, len(items) - 1))
    items.insert(i + 1, copy.deepcopy(items[i]))
    return f"duplicate item {_dotted(path + (i,))}"


def m_rename_key(doc, draw):
    slots = _dict_slots(doc)
    path = _pick(draw, slots)
    key = path[-1]
    i = draw(st.integers(0, len(key)))
    op = draw(st.sampled_from(["insert", "delete", "replace", "swap"]))
    c = draw(st.sampled_from("aeiosx_1"))
    if op == "insert":
        new = key[:i] + c + key[i:]
    elif op == "delete" and i < len(key):
        new = key[:i] + key[i + 1:]
    elif op == "swap" and i + 1 < len(key):
        new = key[:i] + key[i + 1] + key[i] + key[i + 2:]
    else:
        new = key[:i] + c + key[i + 1:]
    parent = _get(doc, path[:-1])
    if new == key or new in parent:
        _skip()
    # keep the order of the keys: rebuild the table
    items = [(new if k == key else k, v) for k, v in parent.items()]
    parent.clear()
    parent.update(items)
    return f"rename key {_dotted(path)} -> {new!r}"


def m_unknown_key(doc, draw):
    path = _pick(draw, _tables(doc))
    table = _get(doc, path)
    value = draw(st.sampled_from([1, "x", 1.5, True]))
    table[UNKNOWN_KEY] = value
    return f"unknown key {_dotted(path + (UNKNOWN_KEY,))} = {value!r}"


def m_deep_nest(doc, draw):
    slots = [p for p, _ in _walk(doc)]
    path = _pick(draw, slots)
    depth = draw(st.sampled_from([1, 2, 10, 100, 1000]))
    kind = draw(st.sampled_from(["array", "table"]))
    _get(doc, path[:-1])[path[-1]] = Nested(_get(doc, path), depth, kind)
    return f"deep nest {_dotted(path)}: {depth} x {kind}"


def _skip():
    raise Skip


def _pick(draw, slots):
    """One of ``slots``; the header and ``[expected]`` one time in ten (they are many)."""
    if not slots:
        _skip()
    main = [p for p in slots if _late(p) == 0]
    rest = [p for p in slots if _late(p) != 0]
    if main and (not rest or draw(st.integers(0, 9)) != 0):
        return draw(st.sampled_from(main))
    return draw(st.sampled_from(rest))


def _dotted(path):
    return ".".join(str(k) for k in path) or "<root>"


#: name -> mutation(doc, draw) -> description
FAMILIES = {
    "delete_key": m_delete_key,
    "delete_table": m_delete_table,
    "change_type": m_change_type,
    "extreme_number": m_extreme_number,
    "empty_string": m_empty_string,
    "long_string": m_long_string,
    "hostile_name": m_hostile_name,
    "duplicate_item": m_duplicate_item,
    "rename_key": m_rename_key,
    "unknown_key": m_unknown_key,
    "deep_nest": m_deep_nest,
}


# ---------------------------------------------------------------------------------------
# Running one spec and checking the contract
# ---------------------------------------------------------------------------------------


class Hung(BaseException):
    """Raised by the alarm (a BaseException, so mechcli's ``except Exception`` passes it)."""


@contextlib.contextmanager
def _time_limit(seconds):
    if not hasattr(signal, "SIGALRM"):  # pragma: no cover (Windows)
        yield
        return

    def _ring(signum, frame):
        raise Hung

    old = signal.signal(signal.SIGALRM, _ring)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@contextlib.contextmanager
def _cwd(path):
    old = os.getcwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(old)


def _snapshot(root, skip):
    """Every file and folder under ``root`` except ``skip``: path -> (size, mtime) of a file,
    None for a folder (creating ``skip`` changes its parent's mtime)."""
    seen = {}
    for dirpath, dirnames, filenames in os.walk(root):
        here = Path(dirpath)
        dirnames[:] = [d for d in dirnames if here / d != skip]
        for name in dirnames + filenames:
            p = here / name
            st_ = p.lstat()
            seen[str(p.relative_to(root))] = (None if p.is_dir() and not p.is_symlink()
                                              else (st_.st_size, st_.st_mtime_ns))
    return seen


def _nonfinite(cell):
    try:
        return not math.isfinite(float(cell))
    except ValueError:
        return False


def _check_csv(path):
    """Problems of one CSV file, as strings (empty when it is well formed)."""
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh, strict=True))
    except (csv.Error, UnicodeDecodeError) as exc:
        return [f"{path.name}: unreadable CSV: {exc}"]
    rows = [r for r in rows if r]
    if not rows:
        return []
    bad = []
    width = len(rows[0])
    widths = sorted({len(r) for r in rows})
    if widths != [width]:
        bad.append(f"{path.name}: field counts {widths}, header {width}")
    cells = [c for r in rows[1:] for c in r if _nonfinite(c)]
    if cells:
        bad.append(f"{path.name}: non-finite cells {sorted(set(cells))}")
    return bad


def _strict_json(text):
    def _reject(name):
        raise ValueError(f"non-finite JSON constant {name}")
    return json.loads(text, parse_constant=_reject)


def contract_violations(proc, out, as_json, before, after):
    """Every way this run broke the exit-code contract (an empty list when it kept it)."""
    bad = []
    code = proc.returncode
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    if "Traceback" in proc.stderr:
        bad.append("traceback on stderr")
    if code not in (0, 2, 3):
        bad.append(f"exit {code}")
    if code in (2, 3):
        if len(lines) != 1 or not lines[0].startswith("mechcli: error: "):
            bad.append(f"stderr is not one 'mechcli: error:' line: {lines[:3]!r}")
    if code == 0:
        stray = [ln for ln in lines if not ln.startswith("mechcli: warning: ")]
        if stray:
            bad.append(f"stderr lines that are not warnings: {stray[:3]!r}")
        for csv_path in sorted(out.rglob("*.csv")) if out.is_dir() else []:
            bad.extend(_check_csv(csv_path))
    if as_json and code in (0, 2, 3):
        try:
            doc = _strict_json(proc.stdout)
        except ValueError as exc:
            bad.append(f"--json stdout is not strict JSON: {exc}: {proc.stdout[:120]!r}")
        else:
            if code != 0 and (not isinstance(doc, dict) or doc.get("exit_code") != code
                              or "error" not in doc):
                bad.append(f"--json error object wrong: {proc.stdout[:120]!r}")
    added = sorted(set(after) - set(before))
    changed = sorted(k for k in set(after) & set(before) if after[k] != before[k])
    removed = sorted(set(before) - set(after))
    if added or changed or removed:
        bad.append(f"wrote outside --out: added {added[:5]}, changed {changed[:5]}, "
                   f"removed {removed[:5]}")
    return bad


def _resolve_references(doc, folder):
    """Relative ``*.toml`` references (``[mobility] kin = "../ch1/x.toml"``) -> absolute."""
    for path, value in list(_walk(doc)):
        if isinstance(value, str) and value.endswith(".toml") and (folder / value).is_file():
            _get(doc, path[:-1])[path[-1]] = str((folder / value).resolve())


def _fill_abs(doc, sandbox):
    for path, value in list(_walk(doc)):
        if isinstance(value, str) and "{abs}" in value:
            _get(doc, path[:-1])[path[-1]] = value.replace("{abs}", str(sandbox))


#: how often each family is drawn: extreme numbers reach the solvers (exit 0/3 and the CSV
#: writers); the others mostly stop in the spec reader (exit 2)
WEIGHTS = {"extreme_number": 4, "change_type": 2, "delete_key": 2, "hostile_name": 2}
FAMILY_NAMES = [f for f in FAMILIES for _ in range(WEIGHTS.get(f, 1))]


def _log(record):
    with open(LOG, "a", encoding="utf-8") as fh:
        fh.write(json.dumps(record, ensure_ascii=False) + "\n")


@pytest.mark.parametrize("cfg", CONFIG_FILES, ids=CONFIG_IDS)
def test_a_mutated_config_keeps_the_exit_code_contract(cfg):
    heavy = str(cfg.relative_to(CONFIGS)) in HEAVY and not SLOW
    run = settings(max_examples=min(PER_CONFIG, HEAVY_EXAMPLES) if heavy else PER_CONFIG,
                   deadline=None, derandomize=True, database=None,
                   suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much,
                                          HealthCheck.data_too_large,
                                          HealthCheck.function_scoped_fixture])
    run(given(data=st.data())(_mutated_run))(cfg)


def _mutated_run(cfg, data):
    i = CONFIG_FILES.index(cfg)
    doc = tomllib.loads(cfg.read_text(encoding="utf-8"))
    command = doc["command"]
    _resolve_references(doc, cfg.parent)
    done = []
    # one mutation mostly: a spec with three is nearly always exit 2 at the first one
    for _ in range(data.draw(st.sampled_from([1, 1, 1, 2, 3]), label="mutations")):
        family = data.draw(st.sampled_from(FAMILY_NAMES), label="family")
        try:
            done.append(FAMILIES[family](doc, data.draw))
        except Skip:
            continue
    as_json = data.draw(st.booleans(), label="--json")
    # names become file names only in plots (path_<name>.png): draw them when a name changed
    named = any(re.search(r"[.]name\b", d) for d in done)
    plots = named or (PLOTS and data.draw(st.integers(0, 9), label="plots") == 0)
    with tempfile.TemporaryDirectory(prefix="fuzz-") as tmp:
        sandbox = Path(tmp).resolve()
        work = sandbox / "w1" / "w2" / "w3"
        work.mkdir(parents=True)
        out = work / "out"
        _fill_abs(doc, sandbox)
        spec = work / cfg.name
        spec.write_text(to_toml(doc), encoding="utf-8")
        args = [command, spec, "--no-animate", "--quiet", "--out", out]
        args += [] if plots else ["--no-plot"]
        args += ["--json"] if as_json else []
        note(f"{CONFIG_IDS[i]}: {done}; mechcli {' '.join(map(str, args))}")
        before = _snapshot(sandbox, out)
        with _cwd(sandbox):
            start = time.perf_counter()
            try:
                with _time_limit(TIMEOUT):
                    proc = run_inprocess(*args)
            except Hung:
                bad = [f"hung: no answer in {TIMEOUT} s"]
                proc = None
            seconds = round(time.perf_counter() - start, 3)
        if proc is not None:
            bad = contract_violations(proc, out, as_json, before, _snapshot(sandbox, out))
        if "matplotlib.pyplot" in sys.modules:  # the autouse fixture runs once per test
            sys.modules["matplotlib.pyplot"].close("all")
    if TRACE:
        with open(TRACE, "a", encoding="utf-8") as fh:
            fh.write(json.dumps({"config": CONFIG_IDS[i], "mutations": done,
                                 "exit": proc.returncode if proc is not None else None,
                                 "stderr": proc.stderr[:200] if proc is not None else "",
                                 "bad": bool(bad), "seconds": seconds}, ensure_ascii=False) + "\n")
    if bad and LOG:
        err = proc.stderr.strip().splitlines() if proc is not None else []
        _log({"config": CONFIG_IDS[i], "mutations": done, "json": as_json, "plots": plots,
              "exit": proc.returncode if proc is not None else None,
              "stderr": err[0][:300] if err else "", "violations": bad})
        return
    assert not bad, (CONFIG_IDS[i], done, proc.returncode if proc else None,
                     proc.stderr if proc else "", bad)


@pytest.mark.parametrize("cfg", [c for c, n in zip(CONFIG_FILES, CONFIG_IDS) if SLOW or n not in HEAVY],
                         ids=[n for n in CONFIG_IDS if SLOW or n not in HEAVY])
def test_every_config_runs_unmutated_through_the_fuzz_harness(cfg, tmp_path):
    """The harness itself (writer, sandbox, references) must not be what fails."""
    doc = tomllib.loads(cfg.read_text(encoding="utf-8"))
    _resolve_references(doc, cfg.parent)
    work = tmp_path / "w1" / "w2" / "w3"
    work.mkdir(parents=True)
    spec, out = work / cfg.name, work / "out"
    spec.write_text(to_toml(doc), encoding="utf-8")
    before = _snapshot(tmp_path, out)
    with _cwd(tmp_path):
        proc = run_inprocess(doc["command"], spec, "--no-plot", "--no-animate", "--quiet",
                             "--json", "--out", out)
    assert proc.returncode == 0, proc.stderr
    assert contract_violations(proc, out, True, before, _snapshot(tmp_path, out)) == []
    assert any(out.rglob("*")), "the run wrote nothing"
