"""Every spec key is described once (``mechcli/templates/keys.toml``) and that one text is
both the key's comment in the templates of ``mechcli new`` and its ``description`` in
``mechcli schema`` (issue 31 §6; :mod:`mechcli.spec.keydocs`)."""

import json
import re
import sys

import pytest

from mechcli.commands.new import TEMPLATE_COMMANDS
from mechcli.spec import keydocs
from mechcli.spec.schema import shipped_schema_text

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def _properties(node, path=()):
    """(dotted path, schema) of every key of a schema, free-form keys as ``*``."""
    for alt in [node] + list(node.get("anyOf", ())):
        for key, sub in alt.get("properties", {}).items():
            yield ".".join(path + (key,)), sub
            yield from _properties(sub, path + (key,))
        if isinstance(alt.get("items"), dict):
            yield from _properties(alt["items"], path)
        if isinstance(alt.get("additionalProperties"), dict):
            yield ".".join(path + ("*",)), alt["additionalProperties"]
            yield from _properties(alt["additionalProperties"], path + ("*",))


@pytest.mark.parametrize("command", TEMPLATE_COMMANDS)
def test_every_key_of_the_schema_has_a_description(command):
    schema = json.loads(shipped_schema_text(command))
    keys = list(_properties(schema))
    assert len(keys) > 30
    for path, sub in keys:
        words = sub.get("description")
        assert isinstance(words, str) and len(words) > 5, (command, path)
        # the catalogue's words, for this command (a typed key: every type's text)
        assert words == keydocs.describe(command, tuple(path.split("."))), (command, path)


def test_the_catalogue_holds_no_stale_key():
    """Every entry describes a key some command's schema or template has."""
    used = {}
    for command in TEMPLATE_COMMANDS:
        for path, _ in _properties(json.loads(shipped_schema_text(command))):
            used.setdefault(path, set()).add(command)
    for path, command in keydocs.template_files().items():
        text = path.read_text(encoding="utf-8")
        for key in _template_keys(text) | _commented_keys(text):
            used.setdefault(key, set()).add(command)
    for section, entries in keydocs.catalogue().items():
        for key in entries:
            commands = [c for c, tables in keydocs.SECTIONS.items() if section in tables]
            alias = [f"case.{key.split('.', 1)[1]}"] if key.startswith("synthesis.") else []
            assert any(used.get(k, set()) & set(commands) for k in [key] + alias), \
                (section, key)


def _commented_keys(text):
    """Dotted paths of the commented-out keys (``# key = value``) of a template."""
    out, table = set(), ()
    for line in text.splitlines():
        header = re.match(r"^(?:# )?\[\[?([A-Za-z0-9_.]+)\]\]?", line)
        if header:
            table = tuple(header.group(1).split("."))
        key = re.match(r"^# ([A-Za-z_][A-Za-z0-9_]*) = ", line)
        if key:
            out.add(".".join(table + (key.group(1),)))
    return out


def _template_keys(text):
    """Dotted paths of the live keys of a template (arrays of tables without an index)."""
    data = tomllib.loads(text)
    out = set()

    def walk(node, path):
        if isinstance(node, dict):
            for k, v in node.items():
                out.add(".".join(path + (k,)))
                walk(v, path + (k,))
        elif isinstance(node, list):
            for v in node:
                if isinstance(v, dict):
                    walk(v, path)
    walk(data, ())
    return out


@pytest.mark.parametrize("path", sorted(keydocs.template_files()), ids=lambda p: p.name)
def test_the_templates_comments_are_the_catalogues(path):
    """The shipped templates are written by :func:`keydocs.annotate`; after a change of
    the catalogue: ``python -m mechcli.spec.keydocs``."""
    command = keydocs.template_files()[path]
    text = path.read_text(encoding="utf-8")
    assert keydocs.annotate(text, command) == text, "run: python -m mechcli.spec.keydocs"
    # every live key of the template is described by the catalogue
    for key in _template_keys(text):
        assert keydocs.describe(command, tuple(key.split("."))), (path.name, key)


def test_a_key_says_the_same_in_the_template_and_in_the_schema():
    """One source: the slider-crank template's comment on l2 is the schema's text for a
    slider-crank, and the schema's description names every type's meaning."""
    text = keydocs.TEMPLATES.joinpath("kin.slider_crank.toml").read_text(encoding="utf-8")
    line = next(ln for ln in text.splitlines() if ln.startswith("l2 = "))
    assert line.split("# ", 1)[1] == "connecting rod BC [units]"
    schema = json.loads(shipped_schema_text("kin"))
    words = schema["properties"]["mechanism"]["properties"]["l2"]["description"]
    assert words == "four_bar: coupler BC [units]; slider_crank: connecting rod BC [units]"


def test_annotate_writes_wraps_and_rewrites_comments():
    text = ('[input]\nomega1 = 3   # an old comment\n'
            '                       #   and its old continuation\n'
            '# n1 = 20\nstart = 0\n[output]\ndigits = 3\n# not = a key, prose\n')
    out = keydocs.annotate(text, "kin")
    lines = out.splitlines()
    assert lines[0].startswith("[input]") and "# the input's motion" in lines[0]
    assert lines[1].startswith("omega1 = 3") and lines[1].index("#") == keydocs.COLUMN
    assert "old" not in out
    assert all(len(ln) <= keydocs.WIDTH for ln in lines)
    assert any(ln.startswith("# n1 = 20") and "[rpm]" in ln for ln in lines)
    assert lines[-1] == "# not = a key, prose"
    assert keydocs.annotate(out, "kin") == out
    # a bracketed unit or default is never split over two lines
    assert not any(re.search(r"\[[^\]]*$", ln) for ln in lines if "#" in ln)


def test_a_key_of_another_command_or_an_unknown_key_has_no_description():
    assert keydocs.describe("cam", ("mechanism", "l1")) is None
    assert keydocs.describe("kin", ("mechanism", "l7")) is None
    assert keydocs.describe("synth", ("case", "kind")) == \
        keydocs.describe("synth", ("synthesis", "kind"))
    assert keydocs.describe("kin", ("expected", "theta3_max_deg")) == \
        keydocs.describe("kin", ("expected", "*"))


def test_the_schema_doc_covers_every_command():
    from tests.conftest import ROOT
    text = (ROOT / "docs" / "schema.md").read_text(encoding="utf-8")
    loop = re.search(r"for c in ([a-z ]+); do", text).group(1).split()
    assert loop == list(TEMPLATE_COMMANDS)
    for command in TEMPLATE_COMMANDS:
        assert re.search(rf"^\| `{command}` \|", text, re.M), command
    assert "keys.toml" in text and "python -m mechcli.spec.keydocs" in text
