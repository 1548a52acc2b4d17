"""report.txt says what was solved (issue 31 §2): the spec's path and SHA-256, the --set
values and the given data as solved (Greek keys as the book's letters, degrees as /(°));
no machine warnings in it (they go to stderr)."""

import hashlib
import re

from tests.conftest import CONFIGS, run_inprocess

EX2_1 = CONFIGS / "ch2" / "ex2-1.toml"


def test_report_txt_names_the_spec_its_hash_the_overrides_and_the_given_data(tmp_path):
    proc = run_inprocess("force", EX2_1, "--no-plot", "-q", "--set", "input.step=2",
                         "--out", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    digest = hashlib.sha256(EX2_1.read_bytes()).hexdigest()[:16]
    head = " ".join(text.split("mechanism.type", 1)[0].split())   # the heading, unwrapped
    assert "Given (spec" in head and digest in head and "--set input.step=2" in head
    assert str(EX2_1).replace(" ", "") in head.replace(" ", "") and "lengths in mm" in head
    rows = {re.split(r"\s{2,}", ln.strip())[0]: re.split(r"\s{2,}", ln.strip())[-1]
            for ln in text.splitlines() if ln.startswith("  ")}
    # the given data as solved: the --set value, not the file's (step = 1)
    assert rows["input.step"] == "2" and rows["input.ω1"] == "10"
    assert rows["mechanism.l1"] == "400" and rows["gravity.g"] == "10"
    assert rows["link[1]"] == "number = 2, mass = 3, J = 0.25"
    assert rows["load[0]"] == "name = Mr, link = 3, torque = -100"
    # [expected] and [output] are not given data
    assert "expected" not in " ".join(rows) and "output.table_step" not in rows


def test_warnings_go_to_stderr_not_into_the_report(tmp_path):
    # 例 5-4 warns (contact ratio below 1 at a' = 255 mm)
    proc = run_inprocess("gear", CONFIGS / "ch5" / "ex5-4.toml", "--no-plot", "-q",
                         "--out", tmp_path)
    assert proc.returncode == 0 and "warning" in proc.stderr
    text = (tmp_path / "report.txt").read_text(encoding="utf-8")
    assert "warning" not in text.lower() and "Given (" in text
