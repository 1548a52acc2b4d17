"""``mechcli schema COMMAND`` stays in step with the spec readers.

The schema is learnt from the readers (``mechcli/spec/schema.py``); these tests
check the other direction: every config of a command validates against its
schema, and a random unknown key in any (not free-form) table of a config is
rejected both by the schema and by the reader (exit 2).  The validator is
``jsonschema`` when it is installed and otherwise the small one below, for the
subset of JSON Schema that ``mechcli.spec.schema`` emits; both run when both can.
"""

import json
import random
import sys

import pytest

from mechcli.spec.schema import COMMANDS, command_schema, schema_text, shipped_schema_text
from tests.conftest import CONFIGS, run_inprocess

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

try:
    import jsonschema
except ImportError:  # pragma: no cover - optional
    jsonschema = None

#: the keywords mechcli.spec.schema emits (the small validator knows exactly these)
KEYWORDS = {"$schema", "title", "description", "type", "properties", "required",
            "additionalProperties", "enum", "const", "minimum", "maximum", "exclusiveMinimum",
            "items", "minItems", "maxItems", "anyOf", "default"}
TYPES = {"object", "array", "string", "number", "integer", "boolean"}


def _is(value, t):
    if t == "object":
        return isinstance(value, dict)
    if t == "array":
        return isinstance(value, list)
    if t == "string":
        return isinstance(value, str)
    if t == "boolean":
        return isinstance(value, bool)
    if t == "integer":
        return isinstance(value, int) and not isinstance(value, bool)
    if t == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    raise AssertionError(t)


def errors(schema, value, where="$"):
    """The places where *value* breaks *schema* (empty: valid)."""
    if schema is True or schema == {}:
        return []
    if schema is False:
        return [f"{where}: not allowed"]
    out = []
    if "anyOf" in schema:
        if all(errors(s, value, where) for s in schema["anyOf"]):
            out.append(f"{where}: matches no alternative")
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(_is(value, t) for t in types):
            return out + [f"{where}: not {schema['type']}"]
    if "const" in schema and value != schema["const"]:
        out.append(f"{where}: not {schema['const']!r}")
    if "enum" in schema and value not in schema["enum"]:
        out.append(f"{where}: not one of {schema['enum']}")
    if _is(value, "number"):
        if "minimum" in schema and value < schema["minimum"]:
            out.append(f"{where}: below {schema['minimum']}")
        if "exclusiveMinimum" in schema and value <= schema["exclusiveMinimum"]:
            out.append(f"{where}: not above {schema['exclusiveMinimum']}")
        if "maximum" in schema and value > schema["maximum"]:
            out.append(f"{where}: above {schema['maximum']}")
    if isinstance(value, list):
        if len(value) < schema.get("minItems", 0) or len(value) > schema.get("maxItems",
                                                                             len(value)):
            out.append(f"{where}: {len(value)} items")
        for i, item in enumerate(value):
            out += errors(schema.get("items", True), item, f"{where}[{i}]")
    if isinstance(value, dict):
        props = schema.get("properties", {})
        out += [f"{where}: missing {k}" for k in schema.get("required", ()) if k not in value]
        for k, v in value.items():
            sub = props.get(k, schema.get("additionalProperties", True))
            out += errors(sub, v, f"{where}.{k}")
    return out


def valid(schema, value):
    mine = not errors(schema, value)
    if jsonschema is not None:
        for cls in (jsonschema.Draft7Validator, jsonschema.Draft202012Validator):
            assert mine == cls(schema).is_valid(value), (cls, mine, value)
    return mine


@pytest.fixture(scope="module")
def schemas():
    """The shipped schemas: what an installed mechcli prints."""
    return {c: json.loads(shipped_schema_text(c)) for c in COMMANDS}


@pytest.mark.parametrize("command", COMMANDS)
def test_shipped_schema_is_what_the_reader_teaches(command):
    """The shipped schema equals the one learnt afresh from the spec reader with every config
    as a seed, so it cannot drift from the reader.  To update it after changing a reader:
    ``mechcli schema COMMAND --learn -o mechcli/schemas/COMMAND.json``."""
    assert schema_text(command_schema(command, configs=CONFIGS)) == shipped_schema_text(command), \
        f"run: mechcli schema {command} --learn -o mechcli/schemas/{command}.json"


def _load(path):
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def _configs(command):
    return [p for p in sorted(CONFIGS.rglob("*.toml")) if _load(p).get("command") == command]


def _tables(schema, node, path=()):
    """(path, table) of every table under *node* that the schema closes."""
    if schema.get("additionalProperties", True) is not False:
        return
    yield path, node
    for key, value in node.items():
        sub = schema.get("properties", {}).get(key, {})
        for alt in sub.get("anyOf", [sub]):
            if isinstance(value, dict) and alt.get("type") == "object":
                yield from _tables(alt, value, path + (key,))
                break
            if isinstance(value, list) and alt.get("type") == "array" \
                    and alt.get("items", {}).get("type") == "object":
                for i, item in enumerate(value):
                    yield from _tables(alt["items"], item, path + (key, str(i)))
                break


def _walk(schema):
    yield schema
    for key in ("items", "additionalProperties"):
        if isinstance(schema.get(key), dict):
            yield from _walk(schema[key])
    for sub in schema.get("properties", {}).values():
        yield from _walk(sub)
    for sub in schema.get("anyOf", ()):
        yield from _walk(sub)


@pytest.mark.parametrize("command", COMMANDS)
def test_schema_is_well_formed(schemas, command):
    schema = schemas[command]
    assert schema["$schema"] == "http://json-schema.org/draft-07/schema#"
    if jsonschema is not None:
        jsonschema.Draft7Validator.check_schema(schema)
        jsonschema.Draft202012Validator.check_schema(schema)
    for node in _walk(schema):
        assert set(node) <= KEYWORDS, set(node) - KEYWORDS
        if "type" in node:
            assert node["type"] in TYPES
        if node.get("type") == "object" and "properties" in node:
            assert set(node.get("required", ())) <= set(node["properties"])
    json.dumps(schema)  # plain JSON
    assert schema["properties"]["command"]["const"] == command
    assert schema["additionalProperties"] is False


@pytest.mark.parametrize("command", COMMANDS)
def test_every_config_validates(schemas, command):
    configs = _configs(command)
    assert configs
    for path in configs:
        assert valid(schemas[command], _load(path)), (path, errors(schemas[command],
                                                                   _load(path)))


@pytest.mark.parametrize("command", COMMANDS)
def test_unknown_key_is_rejected_by_schema_and_reader(schemas, command, tmp_path):
    rng = random.Random(f"schema-{command}")
    schema = schemas[command]
    checked = set()
    for config in _configs(command):
        data = _load(config)
        for path, node in list(_tables(schema, data)):
            key = "zz" + "".join(rng.choice("abcdefghijklmnopqrstuvwxyz_") for _ in range(6))
            node[key] = 1
            assert not valid(schema, data), (config, path, key)
            del node[key]
            # the reader, once per table of the schema (the meta-test
            # tests/textbook/test_unknown_keys.py runs every table of every config)
            pattern = tuple("[]" if p.isdigit() else p for p in path)
            if pattern in checked:
                continue
            checked.add(pattern)
            dotted = ".".join(path + (key,))
            proc = run_inprocess(command, config, "--set", f"{dotted}=1", "--no-plot",
                                 "--quiet", "--out", tmp_path / "out")
            assert proc.returncode == 2, (config, dotted, proc.stderr)
            assert f"unknown key '{key}'" in proc.stderr, proc.stderr
    assert len(checked) >= 3


@pytest.mark.parametrize("command", COMMANDS)
def test_templates_validate(schemas, command):
    from importlib.resources import files
    template = files("mechcli") / "templates" / f"{command}.toml"
    assert template.is_file()   # every command ships a starter spec (mechcli new)
    assert valid(schemas[command], tomllib.loads(template.read_text(encoding="utf-8")))


def test_wrong_values_are_rejected(schemas):
    """Types, choices and bounds come from the accessors' arguments."""
    kin = schemas["kin"]
    spec = _load(CONFIGS / "ch1" / "ex1-1.toml")
    assert valid(kin, spec)
    for path, value in ((("mechanism", "type"), "fourbar"), (("units",), "km"),
                        (("output", "frames"), 1), (("output", "plots"), "yes"),
                        (("mechanism", "l1"), -5), (("command",), "cam")):
        bad = json.loads(json.dumps(spec))
        node = bad
        for p in path[:-1]:
            node = node.setdefault(p, {})
        node[path[-1]] = value
        assert not valid(kin, bad), path
    del spec["mechanism"]
    assert not valid(kin, spec)


def test_cli_prints_and_writes_the_schema(tmp_path):
    proc = run_inprocess("schema", "grashof")
    assert proc.returncode == 0, proc.stderr
    schema = json.loads(proc.stdout)
    assert "fourbar" in schema["properties"]
    out = tmp_path / "gear.schema.json"
    proc = run_inprocess("schema", "gear", "-o", out)
    assert proc.returncode == 0, proc.stderr
    assert "spur" in json.loads(out.read_text(encoding="utf-8"))["properties"]


def test_unknown_command_is_a_usage_error():
    proc = run_inprocess("schema", "kni")
    assert proc.returncode == 2
    assert "did you mean 'kin'" in proc.stderr


def test_recording_is_off_outside_the_schema():
    from mechcli.spec.reader import Section
    assert Section.recorder is None
    command_schema("cam")
    assert Section.recorder is None
