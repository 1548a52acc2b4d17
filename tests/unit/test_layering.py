"""The layers keep their import contract; the core stays pure; start-up stays light.

``cli -> commands -> {spec, report} -> core`` (docs/DESIGN.md §1).  The contract is
checked on the AST of every module (module-level and function-level imports
alike), not on its text:

* ``mechcli.core`` imports nothing of mechcli outside ``mechcli.core`` (so
  nothing of ``spec``, ``report``, ``commands``, ``cli``, ``options``) and
  none of click, rich, matplotlib, PIL, tomllib, tomli.
* ``mechcli.spec`` turns TOML into validated problems and does not solve: it
  imports nothing of ``report``, ``commands``, ``cli``, ``options``, nor a
  user interface or plotting library; from the core it imports only classes
  (problem and element types, errors), constants, and the model-building
  functions named in :data:`SPEC_CORE_FUNCTIONS`.
* ``mechcli.report`` words and draws results and does not solve another
  command's problem: it imports nothing of ``commands``, ``cli``,
  ``options``, nor click (it writes through plain functions and raises plain
  exceptions that the command layer turns into click's); of ``spec`` only what
  :data:`REPORT_SPEC_IMPORTS` allows; from the core only classes (result
  types) and constants, plus the functions named per module in
  :data:`REPORT_CORE_FUNCTIONS`, each of which must live in the core package
  of the report module's own command.
* ``mechcli.runner`` (the batch behind ``mechcli check``, the atlas on disk,
  another command's results in process) is orchestration beside ``commands``:
  each of its modules imports of mechcli only the packages named in
  :data:`RUNNER_IMPORTS`, and no user interface or plotting library; no other
  layer (core, spec, report) imports it.  ``mechcli.batch`` and
  ``mechcli.atlas_store`` are its modules' former names (aliases).
* No two modules import each other (not even inside a function): the pairs
  left are :data:`KNOWN_MUTUAL_IMPORTS`, to be emptied.

What breaks the contract today is listed in :data:`KNOWN_VIOLATIONS`, to be
emptied; an entry that no longer occurs fails the test, so the list only
shrinks.
"""

import ast
import importlib
import inspect
import re
import subprocess
import sys
from pathlib import Path

import mechcli
from tests.conftest import ROOT

#: the package under test: the checkout in development, the installed wheel in CI
PACKAGE = Path(mechcli.__file__).resolve().parent

#: third-party packages the core must never import
CORE_FORBIDDEN_LIBRARIES = {"click", "rich", "matplotlib", "PIL", "tomllib", "tomli"}
#: ... nor the spec layer (it reads TOML, but shows and draws nothing)
SPEC_FORBIDDEN_LIBRARIES = {"click", "rich", "matplotlib", "PIL"}
#: ... nor the report layer the command-line library (it shows tables with rich and
#: draws with matplotlib, but the options and usage errors are the command layer's)
REPORT_FORBIDDEN_LIBRARIES = {"click"}

#: functions of the core the spec layer may call: they build a model from
#: numbers (presets, constructors), they do not solve it
SPEC_CORE_FUNCTIONS = {
    "four_bar", "slider_crank", "guide_bar", "shaper",  # presets (issue 11)
    "topology",            # the pair model of a linkage (which pairs carry forces)
    "actuated_pair",       # the pair an actuator names (a check of the spec, issue 30)
    "pairs_of_links",      # the pairs of links given by their joints (grashof's [mobility])
    "default_quantities",  # the names of the quantities a linkage has
    "stack",               # one batched linkage of a population (optimize's candidates)
    "stream_grid",         # the analysed rows of a streamed kin sweep (a grid, no solve)
    # the elements a drawing describes (type = "joints", issue 30): its Assur groups and
    # each group's branch as drawn, checked on the engine at the drawing's one position
    "from_drawing",
    # optimize's checks before its problem is built (issue 32): the named function of
    # a function goal (evaluated at x0 and xm for its targets) and the four links of a
    # four-bar (the crank constraint needs one); models, not solves
    "make_function",
    "four_bar_lengths",
}

#: what every layer may take from the core besides classes and constants: the decorator
#: that makes the problem and result types (``mechcli.core.records``, a faster
#: ``dataclasses.dataclass(frozen=True)``; it solves nothing)
SHARED_CORE_FUNCTIONS = {("mechcli.core.records", "record")}

#: report module -> the core package of its command (functions only from there)
OWN_CORE = {
    "mechcli.report.kin": "mechcli.core.linkage",
    "mechcli.report.kin_plots": "mechcli.core.linkage",
    "mechcli.report.force": "mechcli.core.linkage",
    "mechcli.report.force_plots": "mechcli.core.linkage",
    "mechcli.report.force_rows": "mechcli.core.linkage",
    "mechcli.report.cam": "mechcli.core.cam",
    "mechcli.report.cam_plots": "mechcli.core.cam",
    "mechcli.report.gear": "mechcli.core.gear",
    "mechcli.report.gear_plots": "mechcli.core.gear",
    "mechcli.report.grashof": "mechcli.core.grashof",
    # the structural analysis of grashof's mobility kind and of a linkage by its joints
    "mechcli.report.structure": "mechcli.core.grashof",
    "mechcli.report.synth": "mechcli.core.synth",
    "mechcli.report.flywheel": "mechcli.core.flywheel",
    "mechcli.report.optimize": "mechcli.core.optimize",
    "mechcli.report.atlas": "mechcli.core.synth",
    "mechcli.report.atlas_plots": "mechcli.core.synth",
    "mechcli.report.optimize_plots": "mechcli.core.optimize",
    # the animation poses the linkage with kin's drawing
    "mechcli.report.flywheel_plots": "mechcli.core.linkage",
    # the pictures draw the designed linkage with kin's drawing, posed by the engine
    "mechcli.report.synth_plots": "mechcli.core.linkage",
    # mechcli check reports plain dicts of the batch and calls no core function;
    # mapped to a core package it does not use
    "mechcli.report.check": "mechcli.core.linkage",
}

#: report module -> core functions it may call: drawing geometry and naming
#: helpers of its own command, never the solver of the problem it reports
REPORT_CORE_FUNCTIONS = {
    "mechcli.report.kin_plots": {"solve"},  # poses of the linkage for the animation frames
    "mechcli.report.synth_plots": {"solve"},  # the design in its positions and frames
    "mechcli.report.flywheel_plots": {"solve"},  # the mechanism in the animation frames
    "mechcli.report.force_plots": {"balancing_symbol"},
    # which extremes are constant to round-off: the core's own rule, not a copy of it
    "mechcli.report.force": {"is_constant", "noise_level"},
    "mechcli.report.cam_plots": {"working_outline"},
    "mechcli.report.gear": {"degrees_minutes_seconds", "format_dms"},
    "mechcli.report.gear_plots": {"gear_outline", "generated_tooth", "ring_outline",
                                 "mesh_positions", "cutter_positions"},
}

#: report module -> spec modules it may import: ``finish`` checks the keys of
#: ``[expected]`` against the results of the run
REPORT_SPEC_IMPORTS = {
    "mechcli.report.run": {"mechcli.spec.common", "mechcli.spec.errors"},
}

#: what breaks the contract today, as "importer -> imported"; empty it, never grow it
KNOWN_VIOLATIONS: set = set()

#: runner module -> the mechcli packages it may import (besides its own package)
RUNNER_IMPORTS = {
    "mechcli.runner": set(),
    # runs each spec through the CLI in this process; compares with spec.expected
    "mechcli.runner.batch": {"mechcli.cli", "mechcli.spec"},
    # writes and reads what the core's atlas computes
    "mechcli.runner.atlas_store": {"mechcli.core"},
    # synth's atlas problems run on the store: the pool or Dask client, the folder, the
    # core's search and refinement, the progress lines (report.console)
    "mechcli.runner.atlas": {"mechcli.core", "mechcli.spec", "mechcli.report"},
    # reads a kin/force problem and computes its --json results as the command does
    "mechcli.runner.results": {"mechcli.spec", "mechcli.core", "mechcli.commands",
                               "mechcli.report"},
    # the former names, aliases of the runner's modules
    "mechcli.batch": set(),
    "mechcli.atlas_store": set(),
}
#: ... and the libraries none of them imports
RUNNER_FORBIDDEN_LIBRARIES = {"click", "rich", "matplotlib", "PIL"}

#: pairs of modules that import each other today; empty it, never grow it
KNOWN_MUTUAL_IMPORTS = {
    ("mechcli.core.linkage.accuracy", "mechcli.core.linkage.sweep"),
    ("mechcli.spec.joints", "mechcli.spec.kin"),
    ("mechcli.spec.reader", "mechcli.spec.schema"),
    ("mechcli.spec.reader", "mechcli.spec.unknown"),
}


def _module_name(path):
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def _modules():
    return {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _tree(path):
    return ast.parse(path.read_text(encoding="utf-8"), str(path))


def _imports(name, path):
    """``(module, imported name or None)`` of every import statement in a module.

    A core module imported as a module (``from mechcli.core.linkage import
    presets``) counts as importing each attribute the importer uses
    (``presets.four_bar`` -> ``mechcli.core.linkage.presets``, ``four_bar``).
    """
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = _tree(path)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, None
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{parent}.{base}" if base else parent
            for alias in node.names:
                submodule = f"{base}.{alias.name}"
                if _within(base, "mechcli.core") and _is_module(submodule):
                    local = alias.asname or alias.name
                    for use in ast.walk(tree):
                        if isinstance(use, ast.Attribute) and isinstance(use.value, ast.Name) \
                                and use.value.id == local:
                            yield submodule, use.attr
                else:
                    yield base, alias.name


def _is_module(name):
    try:
        importlib.import_module(name)
    except ImportError:
        return False
    return True


def _within(module, package):
    return module == package or module.startswith(package + ".")


def _core_object(module, name):
    """(kind, where): kind in module/class/function/constant; where = defining module."""
    if name is None:
        return "module", module
    mod = importlib.import_module(module)
    obj = getattr(mod, name, None)
    if obj is None:
        raise AssertionError(f"{module} has no attribute {name}")
    if inspect.ismodule(obj):
        return "module", obj.__name__
    if inspect.isclass(obj):
        return "class", getattr(obj, "__module__", module)
    if callable(obj):
        return "function", getattr(obj, "__module__", module)
    return "constant", module


def _violations():
    out = set()
    for name, path in _modules().items():
        for module, imported in _imports(name, path):
            top = module.split(".")[0]
            label = f"{name} -> {module}" + (f".{imported}" if imported else "")
            if _within(name, "mechcli.core"):
                if top == "mechcli" and not _within(module, "mechcli.core"):
                    out.add(label)
                if top in CORE_FORBIDDEN_LIBRARIES:
                    out.add(label)
                continue
            if name in RUNNER_IMPORTS:
                if top in RUNNER_FORBIDDEN_LIBRARIES:
                    out.add(label)
                if top == "mechcli" and not any(
                        _within(module, p) for p in RUNNER_IMPORTS[name] | {"mechcli.runner"}):
                    out.add(label)
                continue
            layer = name.split(".")[1] if name.count(".") else ""
            if layer not in ("spec", "report"):
                continue
            if _within(module, "mechcli.runner") or (module, imported) in _RUNNER_ALIASES:
                out.add(label)
            if top in SPEC_FORBIDDEN_LIBRARIES and layer == "spec":
                out.add(label)
            if top in REPORT_FORBIDDEN_LIBRARIES and layer == "report":
                out.add(label)
            if any(_within(module, f"mechcli.{x}") for x in ("commands", "cli", "options")):
                out.add(label)
            if layer == "spec" and _within(module, "mechcli.report"):
                out.add(label)
            if layer == "report" and _within(module, "mechcli.spec") \
                    and module not in REPORT_SPEC_IMPORTS.get(name, ()):
                out.add(label)
            if not _within(module, "mechcli.core"):
                continue
            kind, where = _core_object(module, imported)
            if (where, imported) in SHARED_CORE_FUNCTIONS:
                continue
            if kind == "module":
                out.add(f"{name} -> {where} (module)")
            elif kind == "function":
                if layer == "spec":
                    ok = imported in SPEC_CORE_FUNCTIONS
                else:
                    ok = imported in REPORT_CORE_FUNCTIONS.get(name, ()) \
                        and _within(where, OWN_CORE.get(name, "-"))
                if not ok:
                    out.add(label)
    return out


#: the runner's modules under their former names, as ``from mechcli import batch``
_RUNNER_ALIASES = {("mechcli", "batch"), ("mechcli", "atlas_store"), ("mechcli.batch", None),
                   ("mechcli.atlas_store", None)}


def _mutual_imports():
    """Pairs (a, b), a < b, of modules of which each imports the other."""
    modules = _modules()
    graph = {}
    for name, path in modules.items():
        for module, imported in _imports(name, path):
            for target in (f"{module}.{imported}" if imported else None, module):
                # a module of the package, not the package its importer lives in
                if target in modules and target != name and not _within(name, target):
                    graph.setdefault(name, set()).add(target)
                    break
    return {tuple(sorted((a, b))) for a in graph for b in graph[a] if a in graph.get(b, ())}


def test_no_two_modules_import_each_other():
    """A cycle such as spec.common <-> spec.expected (issue 32) is gone and stays gone."""
    mutual = _mutual_imports()
    assert not mutual - KNOWN_MUTUAL_IMPORTS, sorted(mutual - KNOWN_MUTUAL_IMPORTS)
    assert not KNOWN_MUTUAL_IMPORTS - mutual, \
        ("fixed, remove from KNOWN_MUTUAL_IMPORTS", sorted(KNOWN_MUTUAL_IMPORTS - mutual))


def test_the_runner_package_is_covered():
    """Every runner module has its allow-list; the former names are the same modules."""
    import mechcli.atlas_store
    import mechcli.batch
    import mechcli.runner.atlas_store
    import mechcli.runner.batch
    runner = {m for m in _modules() if _within(m, "mechcli.runner")}
    assert runner | {"mechcli.batch", "mechcli.atlas_store"} == set(RUNNER_IMPORTS)
    assert mechcli.batch is mechcli.runner.batch
    assert mechcli.atlas_store is mechcli.runner.atlas_store


def test_layers_keep_the_import_contract():
    new = _violations() - KNOWN_VIOLATIONS
    assert not new, "imports that break the layer contract (see this module's docstring):\n" \
        + "\n".join(sorted(new))


def test_known_violations_are_not_stale():
    fixed = KNOWN_VIOLATIONS - _violations()
    assert not fixed, "fixed, remove from KNOWN_VIOLATIONS:\n" + "\n".join(sorted(fixed))


def test_allowances_are_used():
    """Every function allowed above is imported by a module it is allowed to (no rot)."""
    used = {}
    for name, path in _modules().items():
        for module, imported in _imports(name, path):
            if imported and _within(module, "mechcli.core"):
                used.setdefault(name, set()).add(imported)
    for name, allowed in REPORT_CORE_FUNCTIONS.items():
        assert allowed <= used.get(name, set()), (name, allowed - used.get(name, set()))
    spec_used = set().union(*(u for n, u in used.items() if n.startswith("mechcli.spec.")))
    assert SPEC_CORE_FUNCTIONS <= spec_used, SPEC_CORE_FUNCTIONS - spec_used


def test_contract_tables_name_real_modules():
    modules = _modules()
    for table in (OWN_CORE, REPORT_CORE_FUNCTIONS, REPORT_SPEC_IMPORTS):
        assert set(table) <= set(modules), set(table) - set(modules)
    assert {m for m in modules if m.startswith("mechcli.report.")
            and not m.startswith("mechcli.report.words.")} - set(OWN_CORE) <= {
        "mechcli.report.console", "mechcli.report.files", "mechcli.report.jsonout",
        "mechcli.report.plotting",
        "mechcli.report.run", "mechcli.report.table", "mechcli.report.tomlout",
        # the CAD files of several commands (--export): it writes what their commands
        # solved and imports nothing of the core
        "mechcli.report.cad",
        # the wording catalogue every report module looks up (its sections are data):
        # words, no core
        "mechcli.report.words"}, \
        "give a new report module its OWN_CORE"


def test_the_contract_catches_what_it_forbids(tmp_path, monkeypatch):
    """The checker itself: a core module importing click, a spec module calling a solver,
    a report module importing click."""
    probe = {"mechcli.core.fake": "import click\nfrom mechcli.spec import errors\n",
             "mechcli.spec.fake": "def f():\n    from mechcli.core.linkage import solve\n",
             "mechcli.runner.atlas_store": "import rich\nfrom mechcli.report import cad\n",
             "mechcli.report.fake": "from mechcli import batch\ndef f():\n    import click\n"}
    found = set()
    for name, text in probe.items():
        path = tmp_path / (name.rpartition(".")[2] + ".py")
        path.write_text(text)
        monkeypatch.setattr(sys.modules[__name__], "_modules", lambda n=name, p=path: {n: p})
        found |= _violations()
    assert found == {"mechcli.core.fake -> click", "mechcli.core.fake -> mechcli.spec.errors",
                     "mechcli.spec.fake -> mechcli.core.linkage.solve",
                     "mechcli.runner.atlas_store -> rich",
                     "mechcli.runner.atlas_store -> mechcli.report.cad",
                     "mechcli.report.fake -> mechcli.batch", "mechcli.report.fake -> click"}


def test_core_does_not_open_files():
    offenders = [p.name for p in (PACKAGE / "core").rglob("*.py")
                 if re.search(r"\bopen\(|\bprint\(", p.read_text(encoding="utf-8"))]
    assert offenders == []


def test_version_does_not_import_numpy_or_matplotlib():
    code = ("import sys; from mechcli import cli;"
            "print(sorted(m for m in ('numpy','matplotlib','scipy','rich') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.strip()
    assert out == "[]"


def test_the_design_it_cites_is_in_the_repo():
    """The contract above cites docs/DESIGN.md §1; it names every layer and the runner."""
    text = (ROOT / "docs" / "DESIGN.md").read_text(encoding="utf-8")
    section = text.split("## 1. Layout", 1)[1].split("\n## 2.", 1)[0]
    for package in ("commands/", "spec/", "core/", "report/", "runner/"):
        assert package in section, package
