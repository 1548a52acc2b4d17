"""The package a user installs: every third-party module mechcli imports is a declared
dependency, and the package data the commands read is declared (issue 21 item 13)."""

import ast
import sys

import mechcli
from tests.conftest import ROOT

try:
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python < 3.11
    import tomli as tomllib

#: import name -> distribution name, where they differ
DISTRIBUTION = {"PIL": "pillow"}


def _imported_top_level_modules():
    package = __import__("pathlib").Path(mechcli.__file__).resolve().parent
    names = set()
    for path in package.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names.update(a.name.split(".")[0] for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    # tomllib: the standard library's from Python 3.11 (tomli before it, a dependency)
    # typing_extensions: imported only under TYPE_CHECKING (core/records.py's
    # dataclass_transform), for type checkers; never at run time
    return names - _stdlib() - {"mechcli", "tomli", "tomllib", "typing_extensions"} \
        - CPYTHON_BUILTINS


def _stdlib():
    """The standard library's top-level modules (sys.stdlib_module_names from Python 3.10;
    before it, every module found in the interpreter's own library folder)."""
    if hasattr(sys, "stdlib_module_names"):
        return set(sys.stdlib_module_names)
    import pkgutil
    import sysconfig
    lib = sysconfig.get_paths()["stdlib"]
    return set(sys.builtin_module_names) | {m.name for m in pkgutil.iter_modules([lib])} | {
        m.name for m in pkgutil.iter_modules([lib + "/lib-dynload"])}


#: CPython's built-in SHA-256 under its names before and from 3.12 (report/files.py tries
#: both, then hashlib): stdlib, though sys.stdlib_module_names lists only the running one's
CPYTHON_BUILTINS = {"_sha256", "_sha2"}


#: import name -> the optional extra that provides it (imported only on that path)
OPTIONAL = {"dask": "dask", "pandas": "pandas", "ezdxf": "cad"}


def _declared():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    out = set()
    for req in project["dependencies"]:
        name = req.split(";")[0]
        for sep in "<>=!~[ ":
            name = name.split(sep)[0]
        out.add(name.strip().lower())
    return out, project


def test_every_imported_third_party_module_is_a_dependency():
    declared, _ = _declared()
    imported = {DISTRIBUTION.get(m, m).lower() for m in _imported_top_level_modules()}
    assert imported, "the AST walk found no third-party import at all"
    extras = project_extras()
    optional = {m for m in imported if m in OPTIONAL and any(
        r.lower().startswith(m) for r in extras.get(OPTIONAL[m], []))}
    assert imported - declared - optional == set()


def project_extras():
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))[
        "project"]["optional-dependencies"]


def test_published_metadata():
    _, project = _declared()
    for key in ("readme", "license", "authors", "classifiers", "requires-python", "description"):
        assert project.get(key), key
    assert "tomli>=1.1; python_version < '3.11'" in project["dependencies"]


def test_package_data_of_new_and_schema_is_declared():
    data = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    globs = data["tool"]["setuptools"]["package-data"]["mechcli"]
    package = __import__("pathlib").Path(mechcli.__file__).resolve().parent
    for folder, pattern in (("templates", "*.toml"), ("templates/examples", "*.toml"),
                            ("schemas", "*.json")):
        assert f"{folder}/{pattern}" in globs
        assert list((package / folder).glob(pattern)), folder


def test_the_license_is_a_file_of_the_package():
    """pyproject's license = "MIT" ships its text: LICENSE, named in license-files."""
    _deps, project = _declared()
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License") and "WITHOUT WARRANTY OF ANY KIND" in text


def test_the_allocator_setting_is_a_no_op_off_linux(monkeypatch):
    """On Windows ``ctypes.CDLL(None)`` raises TypeError (CPython issue 83424): the
    setting must give up quietly there, never crash a command (review of issue 17)."""
    import ctypes
    import sys

    from mechcli import _alloc

    monkeypatch.setattr(_alloc, "_done", False)
    monkeypatch.setattr(sys, "platform", "win32")
    assert _alloc.keep_heap_warm() is False

    def windows_cdll(name, *a, **k):          # what CPython's Windows branch does
        if "/" in name:
            pass
        raise OSError(name)

    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setattr(ctypes, "CDLL", windows_cdll)
    assert _alloc.keep_heap_warm() is False
