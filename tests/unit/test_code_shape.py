"""The shape issue 32 gave the code, kept: no function longer than a screen or two and
thin commands.  A helper's annotations pushed flywheel's ``steady_state`` to 104 lines
without anyone noticing: this test notices."""

import ast
from pathlib import Path

import mechcli

PACKAGE = Path(mechcli.__file__).resolve().parent
#: longest function, in lines from its ``def`` to its last line (docstring included)
MAX_FUNCTION = 100
#: longest command module: a command reads its spec, calls the core, hands the result on
MAX_COMMAND = 200


def _functions(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node.name, node.end_lineno - node.lineno + 1


def test_no_function_is_longer_than_MAX_FUNCTION_lines():
    long = [f"{p.relative_to(PACKAGE)}:{name} ({n} lines)"
            for p in sorted(PACKAGE.rglob("*.py")) for name, n in _functions(p)
            if n > MAX_FUNCTION]
    assert not long, "split along its seams: " + ", ".join(long)


def test_every_command_module_is_a_page():
    commands = sorted((PACKAGE / "commands").glob("*.py"))
    assert len(commands) >= 8
    big = [f"{p.name} ({n})" for p in commands
           if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_COMMAND]
    assert not big, big


def test_the_measure_sees_a_long_function(tmp_path):
    """The checker itself: a 101-line function is found."""
    body = "\n".join(f"    x{i} = {i}" for i in range(100))
    (tmp_path / "m.py").write_text(f"def f():\n{body}\n", encoding="utf-8")
    assert dict(_functions(tmp_path / "m.py")) == {"f": 101}
