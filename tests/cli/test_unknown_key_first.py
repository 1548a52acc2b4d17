"""A misspelt key is the key named (issue 34 §5): an unknown key is reported before any
check that depends on the keys present (mechcli.spec.unknown, on the error path of
mechcli.cli.main), with the key it most likely meant."""

import random
import re

import pytest

from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec

try:
    import tomllib
except ImportError:      # Python < 3.11
    import tomli as tomllib


def _renamed(path, old, new):
    text = path.read_text(encoding="utf-8")
    out, n = re.subn(rf"(?m)^{re.escape(old)}(\s*=)", rf"{new}\1", text, count=1)
    assert n == 1, (path, old)
    return out


@pytest.mark.parametrize("config,old,new,hint", [
    ("ch4/ex4-1.toml", "r0", "0r", "r0"),                    # said: unknown key 'rr'
    ("ch3/rrrrp-example.toml", "l2", "2l", "l2"),            # blamed l3
    ("ch3/exercise3-13.toml", "method", "mthod", "method"),  # reported a side effect on n
    ("ch6/ex6-4-book.toml", "phi_deg", "pi_deg", "phi_deg"),  # blamed J
    ("ch5/loads-spur.toml", "power_kW", "poewr_kW", "power_kW"),
    ("ch5/chordal-helical.toml", "beta_deg", "beta_ddeg", "beta_deg"),
])
def test_the_misspelt_key_is_named(tmp_path, config, old, new, hint):
    path = CONFIGS / config
    spec = write_spec(tmp_path, _renamed(path, old, new), name=path.name)
    command = tomllib.loads(path.read_text(encoding="utf-8"))["command"]
    proc = run_inprocess(command, spec, "--out", tmp_path / "o", "--no-plot", "--quiet")
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert f"'{new}'" in line and f"did you mean '{hint}'" in line, line


def _plain_keys(data, path=()):
    """(dotted path, key) of every plain key in a spec's tables, skipping the tables
    whose keys are names (a ground point, a joint, an expected result)."""
    for key, value in data.items():
        if isinstance(value, dict):
            if key not in ("ground", "joints", "expected"):
                yield from _plain_keys(value, path + (key,))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            continue
        elif path or key not in ("command",):
            yield path, key


def test_a_key_renamed_anywhere_is_named(tmp_path):
    # one top-level-table key of 24 configs (seeded), each renamed with two letters swapped
    rng = random.Random(34)
    configs = sorted(p for p in CONFIGS.rglob("*.toml") if "atlas" not in p.parts)
    for path in rng.sample(configs, 24):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        keys = [(p, k) for p, k in _plain_keys(data) if len(k) > 1 and len(set(k)) > 1]
        if not keys:
            continue
        where, key = rng.choice(keys)
        new = key[1] + key[0] + key[2:]
        if new == key or new in (data if not where else data[where[0]]):
            continue
        text = path.read_text(encoding="utf-8")
        if len(re.findall(rf"(?m)^{re.escape(key)}\s*=", text)) != 1:
            continue       # the key is in several tables: renaming one is ambiguous here
        spec = write_spec(tmp_path, _renamed(path, key, new), name=path.name)
        proc = run_inprocess(data["command"], spec, "--out", tmp_path / "o", "--no-plot",
                             "--quiet", "--no-animate")
        assert proc.returncode == 2, (path, key, new, proc.stderr)
        assert f"'{new}'" in one_line_error(proc), (path, key, new, proc.stderr)
