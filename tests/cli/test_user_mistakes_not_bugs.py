"""A user's mistake is never called a bug: a bad ``--out`` and a misspelled required key
exit 2 with one line naming what is wrong (issue 18, item 3)."""

import errno
import json
import os

import pytest

from mechcli.spec.errors import SpecError
from mechcli.spec.reader import Section
from tests.conftest import CONFIGS, one_line_error, run_inprocess, write_spec

EX1_1 = CONFIGS / "ch1" / "ex1-1.toml"


def _assert_json_error(proc, *fragments):
    doc = json.loads(proc.stdout)
    assert doc["command"] == "kin" and doc["exit_code"] == 2
    for f in fragments:
        assert f in doc["error"], doc["error"]


@pytest.mark.parametrize("flag", ["--out", "-o"])
def test_out_under_a_regular_file_is_a_usage_error(tmp_path, flag):
    afile = tmp_path / "notes.txt"
    afile.write_text("mine\n")
    out = afile / "sub"
    proc = run_inprocess("kin", EX1_1, "-q", flag, out)
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert line == (f"mechcli: error: --out: expected a folder where mechcli can write kin.csv, "
                    f"got {out}: Not a directory ({afile} is a file, not a folder)")
    assert "bug" not in line and "internal" not in line
    assert afile.read_text() == "mine\n"
    proc = run_inprocess("kin", EX1_1, "--json", flag, out)
    assert proc.returncode == 2
    _assert_json_error(proc, f"{afile} is a file, not a folder")


def test_unwritable_out_is_a_usage_error(tmp_path, monkeypatch):
    """A folder the OS refuses (EACCES), simulated so that the test also fails as root."""
    from mechcli.report import files
    out = tmp_path / "locked"

    def refuse(path):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(path.parent))
    monkeypatch.setattr(files, "_temporary", refuse)
    proc = run_inprocess("kin", EX1_1, "-q", "-o", out)
    assert proc.returncode == 2, proc.stderr
    line = one_line_error(proc)
    assert line.startswith("mechcli: error: --out: expected a folder where mechcli can write "
                           f"kin.csv, got {out}: Permission denied (no permission"), line
    proc = run_inprocess("kin", EX1_1, "--json", "--out", out)
    assert proc.returncode == 2
    _assert_json_error(proc, str(out), "Permission denied")


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0,
                    reason="root may write into a read-only folder")
def test_read_only_folder_is_a_usage_error(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o555)
    try:
        proc = run_inprocess("kin", EX1_1, "-q", "-o", locked / "sub")
    finally:
        locked.chmod(0o755)
    assert proc.returncode == 2, proc.stderr
    assert "Permission denied" in one_line_error(proc)


def test_short_out_option_writes_there(tmp_path):
    proc = run_inprocess("kin", EX1_1, "--json", "--no-plot", "-o", tmp_path / "short")
    assert proc.returncode == 0, proc.stderr
    files = json.loads(proc.stdout)["files"]
    assert files and all(f.startswith(str(tmp_path / "short")) for f in files)
    assert (tmp_path / "short" / "kin.csv").is_file()


@pytest.mark.parametrize("typo", ["lenght2", "length2", "len2", "l22"])
def test_misspelled_required_key_names_the_typo_and_the_key(tmp_path, typo):
    text = EX1_1.read_text(encoding="utf-8")
    assert "\nl2 = 254" in text
    spec = write_spec(tmp_path, text.replace("\nl2 = 254", f"\n{typo} = 254"))
    proc = run_inprocess("kin", spec, "-q", "-o", tmp_path / "out")
    assert proc.returncode == 2, proc.stderr
    assert one_line_error(proc) == (
        f"mechcli: error: {spec}: [mechanism] {typo}: expected the required key 'l2' "
        f"(missing), got unknown key '{typo}' (did you mean 'l2'?)")
    assert not (tmp_path / "out").exists()


def test_missing_required_key_without_a_typo_says_required(tmp_path):
    text = EX1_1.read_text(encoding="utf-8").replace("\nl2 = 254", "\n")
    spec = write_spec(tmp_path, text)
    proc = run_inprocess("kin", spec, "-q", "-o", tmp_path / "out")
    assert proc.returncode == 2
    assert one_line_error(proc).endswith(
        "[mechanism] l2: expected this key (it is required), got nothing")


def test_unknown_optional_key_spelt_out_gets_its_did_you_mean():
    sec = Section({"l1": 1.0, "lenght6": 2.0}, "s.toml", "mechanism")
    sec.number("l1")
    assert sec.number("l6", None) is None
    with pytest.raises(SpecError) as err:
        sec.finish()
    assert str(err.value.format()).endswith("got unknown key 'lenght6' (did you mean 'l6'?)")


def test_a_different_link_number_is_not_proposed():
    """``l3`` is not a spelling of the missing ``l2``: the message says only "required"."""
    sec = Section({"l1": 1.0, "lenght3": 2.0}, "s.toml", "mechanism")
    sec.number("l1")
    with pytest.raises(SpecError) as err:
        sec.number("l2")
    assert "it is required" in err.value.format()
