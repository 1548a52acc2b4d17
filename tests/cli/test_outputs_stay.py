"""Outputs that stay (issue 31 §2): a figure written from the same spec contents and the
same --set values is kept by a --no-plot rerun and listed in its manifest as kept; a
changed spec or other --set values make it stale (removed, as before)."""

import json

from tests.conftest import CONFIGS, run_inprocess

EX = (CONFIGS / "ch1" / "ex1-1.toml").read_text(encoding="utf-8")


def _run(spec, out, *args):
    proc = run_inprocess("kin", spec, "--out", out, "--json", *args)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def _manifest(out):
    return {e["name"]: e for e in json.loads((out / "outputs.json").read_text())["files"]}


def test_a_no_plot_rerun_keeps_the_figure_of_the_same_problem(tmp_path):
    spec, out = tmp_path / "ex.toml", tmp_path / "o"
    spec.write_text(EX, encoding="utf-8")
    first = _run(spec, out)
    png = (out / "kin.png").read_bytes()
    assert str(out / "kin.png") in first["files"]
    for _ in range(2):     # kept again by a second rerun: the manifest still lists it
        doc = _run(spec, out, "--no-plot")
        assert doc["kept"] == ["kin.png"] and doc["removed"] == []
        assert (out / "kin.png").read_bytes() == png
        entry = _manifest(out)["kin.png"]
        assert entry["kept"] is True and len(entry["sha256"]) == 64
    assert "kept" not in _manifest(out)["kin.csv"]     # written by this run


def test_other_set_values_or_an_edited_spec_make_it_stale(tmp_path):
    spec, out = tmp_path / "ex.toml", tmp_path / "o"
    spec.write_text(EX, encoding="utf-8")
    _run(spec, out, "--set", "input.step=2")
    doc = _run(spec, out, "--no-plot")                  # other --set values
    assert doc["removed"] == ["kin.png"] and doc["kept"] == []
    assert not (out / "kin.png").exists()
    _run(spec, out)
    spec.write_text(EX.replace("step = 1", "step = 2", 1), encoding="utf-8")
    doc = _run(spec, out, "--no-plot")                  # the spec's contents changed
    assert doc["removed"] == ["kin.png"]
