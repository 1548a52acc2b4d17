"""A mistyped key is never silently ignored: every table of every config rejects one.

For each config in ``configs/`` and each table in it (the top level, nested
tables, inline tables, every element of an array of tables, ``[expected]``
and its ``{ value = …, tol = … }`` entries) a copy of the config gets one
extra key ``zz_unknown_key = 1``; the run must exit 2 with a one-line message
that names the key.  The copy is written by a small TOML writer (everything as
inline values at the top level), so the rest of the file reads back
unchanged.  An unknown key in ``[expected]`` is caught only after the run, by
comparing it with the results, so those cases run the whole problem (no
pictures).
"""

import shutil
import sys

import pytest

from tests.conftest import CONFIGS, run_inprocess
from tests.tomlwrite import to_toml as dumps

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

KEY = "zz_unknown_key"

#: tables whose keys are names chosen by the user, so that any key is valid by
#: design (table pattern, array indices written ``[]``) -> why
FREE_FORM = {
    "mechanism.ground": "every key is the name of a ground point (A = [0, 0])",
    "mechanism.joints": "every key is the name of a joint of the drawing (B = [50, 88])",
}




def _tables(node, path=(), pattern=()):
    """(path, pattern) of every table under *node*; path holds list indices."""
    yield path, pattern
    for key, value in node.items():
        if isinstance(value, dict):
            yield from _tables(value, path + (key,), pattern + (key,))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for i, item in enumerate(value):
                yield from _tables(item, path + (key, i), pattern + (key + "[]",))


def _load(path):
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def _cases():
    for config in sorted(CONFIGS.rglob("*.toml")):
        name = str(config.relative_to(CONFIGS))
        for path, pattern in _tables(_load(config)):
            if ".".join(pattern) in FREE_FORM:
                continue
            where = ".".join(map(str, path)) or "(top level)"
            yield pytest.param(config, path, id=f"{name}:{where}")


CASES = list(_cases())


def test_writer_round_trips_every_config():
    for config in sorted(CONFIGS.rglob("*.toml")):
        data = _load(config)
        assert tomllib.loads(dumps(data)) == data, config


def test_free_form_tables_exist():
    """Every exclusion names a table some config has (no stale exclusion)."""
    seen = {".".join(pattern) for config in CONFIGS.rglob("*.toml")
            for _path, pattern in _tables(_load(config))}
    assert set(FREE_FORM) <= seen


@pytest.mark.parametrize("config, path", CASES)
def test_unknown_key_is_rejected(config, path, tmp_path):
    data = _load(config)
    node = data
    for part in path:
        node = node[part]
    node[KEY] = 1
    # a config may name another config by a relative path: copy the whole tree
    shutil.copytree(CONFIGS, tmp_path / "configs")
    spec = tmp_path / "configs" / config.relative_to(CONFIGS)
    spec.write_text(dumps(data), encoding="utf-8")
    out = tmp_path / "out"
    proc = run_inprocess(data["command"], spec, "--no-plot", "--no-animate", "--quiet",
                         "--out", out)
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert proc.returncode == 2, proc.stderr
    assert len(lines) == 1 and f"unknown key '{KEY}'" in lines[0], proc.stderr
    assert str(spec) in lines[0]
    table = ".".join(map(str, path))
    assert (f"[{table}] {KEY}" if table else f": {KEY}:") in lines[0]
    # a failed run leaves none of its output behind
    assert not out.exists() or not [p for p in out.rglob("*") if p.is_file()]
