"""A spec never chooses where mechcli writes (issue 34 §3): `[synthesis] directory` is a
folder inside --out; only the command line's --atlas DIR builds an atlas elsewhere;
reading an atlas a spec names stays allowed."""

from tests.conftest import one_line_error, run_inprocess, write_spec

BUILD = """
command = "synth"
[synthesis]
kind = "atlas_build"
A = [2, 3, 2]
B = [2, 3, 2]
C = [2, 3, 2]
grid_x = [-1, 1, 2]
grid_y = [0, 1, 2]
"""


def test_a_directory_outside_out_is_exit_2_and_nothing_is_written(tmp_path):
    for bad in ("../evil-atlas", "/tmp/evil-atlas", "a/../../evil", ""):
        spec = write_spec(tmp_path, BUILD + f'directory = "{bad}"\n')
        proc = run_inprocess("synth", spec, "--out", tmp_path / "o", "--no-plot")
        assert proc.returncode == 2, (bad, proc.stderr)
        assert "[synthesis] directory" in one_line_error(proc) and "--atlas DIR" in proc.stderr
    assert not (tmp_path / "evil-atlas").exists() and not (tmp_path / "o").exists()


def test_the_atlas_goes_inside_out_or_where_the_command_line_says(tmp_path):
    spec = write_spec(tmp_path, BUILD + 'directory = "mine"\n')
    proc = run_inprocess("synth", spec, "--out", tmp_path / "o", "--no-plot", "--quiet")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "o" / "mine" / "manifest.json").is_file()
    proc = run_inprocess("synth", spec, "--out", tmp_path / "o2", "--no-plot", "--quiet",
                         "--atlas", tmp_path / "shared")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "shared" / "manifest.json").is_file()
    assert not (tmp_path / "o2" / "mine").exists()
    # a file where the folder should be: exit 2 naming the option
    (tmp_path / "file").write_text("x", encoding="utf-8")
    proc = run_inprocess("synth", spec, "--out", tmp_path / "o3", "--no-plot",
                         "--atlas", tmp_path / "file")
    assert proc.returncode == 2 and "--atlas" in one_line_error(proc)
    proc = run_inprocess("synth", spec, "--out", tmp_path / "o4", "--no-plot", "--atlas", "")
    assert proc.returncode == 2 and "--atlas" in one_line_error(proc)
