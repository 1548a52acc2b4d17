"""``mechcli new COMMAND --type TYPE``: a starter spec for every problem type of every
command, which runs as written, checks clean and carries no [expected] values of a book
example (issue 31 §3, §6).

Every template is run in-process through its command and through ``mechcli check``; the
comment that shows how to add one's own [expected] values names results the command
really gives (uncommented with absurd values, ``check`` fails on them: exit 4).
"""

import json
import re
import sys

import pytest

from mechcli.commands.new import TEMPLATE_COMMANDS, TYPES, template_name
from tests.conftest import one_line_error, run_inprocess

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ALL = [(c, t) for c in TEMPLATE_COMMANDS for t in TYPES[c]]
#: the template of synth's path search builds the default atlas (151,690 curves, ~6 s) as
#: written; `check` runs it on the small atlas of the atlas_build template instead
SLOW = {("synth", "path")}


def _enum(schema, *path):
    node = schema
    for key in path:
        node = node["properties"][key]
    return set(node.get("enum") or [v for a in node.get("anyOf", ()) for v in a.get("enum", ())])


def test_the_types_are_the_specs_own():
    """Each command's types are what its spec reader takes: the mechanism types, the
    problem tables, the kinds (from the readers' constants or their learnt schemas)."""
    from mechcli.spec import gear, grashof, kin, optimize, synth
    from mechcli.spec.schema import shipped_schema_text
    assert set(TEMPLATE_COMMANDS) == {"kin", "force", "grashof", "cam", "gear", "synth",
                                      "flywheel", "optimize"}
    assert set(TYPES["kin"]) == set(TYPES["force"]) == set(kin.MECHANISMS)
    assert set(TYPES["grashof"]) == set(grashof.PROBLEMS)
    assert set(TYPES["gear"]) == set(gear.KINDS)
    assert set(TYPES["synth"]) == set(synth.KINDS) | set(synth.ATLAS_KINDS)
    assert set(TYPES["optimize"]) == set(optimize.OBJECTIVES)
    cam = json.loads(shipped_schema_text("cam"))
    followers = {f"{m}_{c}" for m in _enum(cam, "follower", "motion")
                 for c in _enum(cam, "follower", "contact")}
    assert set(TYPES["cam"]) == followers - {"oscillating_flat"}   # flat: translating only
    flywheel = json.loads(shipped_schema_text("flywheel"))
    assert _enum(flywheel, "motion", "kind") <= set(TYPES["flywheel"])


@pytest.fixture(scope="module")
def small_atlas(tmp_path_factory):
    """The atlas the atlas_build template builds (3,330 curves, a fraction of a second)."""
    out = tmp_path_factory.mktemp("atlas")
    spec = out / "build.toml"
    assert run_inprocess("new", "synth", "--type", "atlas_build", "-o", spec).returncode == 0
    proc = run_inprocess("synth", spec, "--quiet", "--no-plot", "--out", out / "o")
    assert proc.returncode == 0, proc.stderr
    return out / "o" / "atlas"


def _footer(text):
    """The [expected] table the template's closing comment shows, uncommented."""
    lines = text.splitlines()
    start = lines.index("#   [expected]")
    block = []
    for ln in lines[start:]:
        if not ln.startswith("#   "):
            break
        block.append(ln[4:])
    return "\n".join(block)


@pytest.mark.parametrize("command, kind", ALL)
def test_every_type_runs_as_written_and_checks_clean(tmp_path, command, kind, small_atlas):
    spec = tmp_path / f"{command}-{kind}.toml"
    proc = run_inprocess("new", command, "--type", kind, "-o", spec)
    assert proc.returncode == 0, proc.stderr
    text = spec.read_text(encoding="utf-8")
    assert text.startswith(f"# mechcli {command}")
    data = tomllib.loads(text)
    assert data["command"] == command
    # no [expected] values left from a book example; the comment shows how to add them
    assert "expected" not in data
    # the editor's schema accepts it (the keys and types `mechcli schema` gives)
    from mechcli.spec.schema import shipped_schema_text
    from tests.cli.test_schema import errors
    assert not errors(json.loads(shipped_schema_text(command)), data)
    assert "mechcli check THIS.toml" in text and "#   [expected]" in text
    # the template runs as written
    proc = run_inprocess(command, spec, "--json", "--no-plot", "--quiet",
                         "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    results = json.loads(proc.stdout)["results"]
    sets = ["--set", f'synthesis.atlas="{small_atlas.as_posix()}"'] if (command, kind) in SLOW \
        else []
    proc = run_inprocess("check", spec, "-j", "1", "--quiet", *sets)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    # the comment's example names real results: uncommented with absurd numbers, check fails
    example = tomllib.loads(_footer(text).replace("...", "1e9"))["expected"]
    assert set(example) <= set(results), set(example) - set(results)
    mine = tmp_path / "mine.toml"
    mine.write_text(text + "\n" + _footer(text).replace("...", "1e9") + "\n", encoding="utf-8")
    proc = run_inprocess("check", mine, "-j", "1", "--quiet", *sets)
    assert proc.returncode == (4 if "..." in _footer(text) else 0), proc.stdout + proc.stderr


def test_the_default_type_is_the_command_template():
    for command in TEMPLATE_COMMANDS:
        assert template_name(command) == template_name(command, TYPES[command][0]) \
            == f"{command}.toml"
        plain = run_inprocess("new", command).stdout
        typed = run_inprocess("new", command, "--type", TYPES[command][0]).stdout
        assert plain == typed and plain.startswith(f"# mechcli {command}")


def test_every_type_has_a_template_and_no_template_is_unlisted():
    from importlib.resources import files
    shipped = {p.name for p in (files("mechcli") / "templates").iterdir()
               if p.name.endswith(".toml") and p.name != "keys.toml"}
    assert shipped == {template_name(c, t) for c, t in ALL}


@pytest.mark.parametrize("args, words", [
    (("kin", "--type", "slider-crank"), ["no type 'slider-crank' for kin",
                                         "did you mean 'slider_crank'", "four_bar"]),
    (("gear", "--type", "helix"), ["no type 'helix' for gear", "helical"]),
    (("kin", "--type", "shaper", "--from", "ex1-4"), ["--type and --from"]),
])
def test_a_bad_type_is_a_usage_error(args, words):
    proc = run_inprocess("new", *args)
    assert proc.returncode == 2
    line = one_line_error(proc)
    for w in words:
        assert w in line


@pytest.mark.parametrize("command", ["new", "schema"])
def test_help_lists_all_eight_commands(command):
    proc = run_inprocess(command, "--help")
    assert proc.returncode == 0
    text = " ".join(proc.stdout.split())
    listed = re.search(r"COMMAND's spec \(([^)]*)\)|COMMAND \(([^)]*)\)", text)
    assert listed, text
    names = [n.strip() for n in (listed.group(1) or listed.group(2)).split(",")]
    assert names == list(TEMPLATE_COMMANDS)
    if command == "new":   # and every type of each
        for c, t in ALL:
            assert t in text, (c, t)
