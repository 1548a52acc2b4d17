"""The Newton-solved Assur group (mechcli.core.linkage.newton_group, built by
drawing._Builder._newton_group) on drawings the configs do not cover: a prismatic pair
between two links of one group, a guide that is a known moving link, a compound hinge
inside a group, a block carrying two joints, a class-III group driven through a
slider-crank; their kinetostatics; drawings at a dead point.

Every drawing is one of configs/ch1's (class3-slider, class4-group, class3-two-cranks)
changed as each case says.  Where the numbers come from:

* positions, velocities, accelerations of the joints and the slides: the independent
  solution tests/reference/independent_joints.py (MINPACK on the joints' coordinates,
  its own continuation from the drawing in 0.25° steps, central differences in the crank
  angle; no mechcli import), to 1e-12 of the peak (positions), 1e-7 (velocities: step
  1e-5 rad) and 1e-6 (accelerations: Richardson on 1e-3/2e-3 rad);
* the dead points that end a partial sweep: the reference's continuation reaches 1e-6 rad
  short of the angle mechcli reports and fails 1e-4 rad beyond it;
* kinetostatics: the balancing torque from the pair equations against virtual power
  (JSON ``power_balance_residual``, Σ P = 0 to round-off), and the same mechanism drawn
  with a prismatic pair's block and guide swapped (the same constraint: the two links
  keep their angle and translate along one direction) must need the same torque.
"""

import json
import math

import numpy as np
import pytest

from mechcli.core.linkage import DriverMotion, solve
from mechcli.core.linkage.newton_group import NewtonGroup
from mechcli.spec.kin import load_kin_spec
from tests.conftest import CONFIGS, ROOT, load_module, one_line_error, run_inprocess, run_json

REF = load_module(ROOT / "tests" / "reference" / "independent_joints.py")


def _drawing(config, *changes):
    """configs/ch1/<config>.toml without its [expected], each (old, new) replaced once."""
    text = (CONFIGS / "ch1" / f"{config}.toml").read_text(encoding="utf-8")
    text = text.split("[expected]")[0]
    for old, new in changes:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return text


NO_RANGE = ("start = -175\nstop = 130\n", "")
PARTIAL = ("step = 1\n", "step = 1\npartial = true\n")

#: (1) a prismatic pair between two links of one group: class3-sixbar's rocker G-E is a
#: block 4 turning about the frame pivot G, through which the ternary link (now the
#: binary C-F) slides along a line fixed in it (drawn through G at 158°): the guide is
#: an unknown body, its line turning with it
INNER_SLIDER = _drawing(
    "class3-slider", NO_RANGE,
    ('E = [117.78, 50.71]\n', 'G = [188.83, 22.69]\n'),
    ('joints = ["C", "E", "F"]     # θ3: the direction C -> E', 'joints = ["C", "F"]'),
    ('joints = ["E"]               # the block, pinned to the ternary link at E',
     'joints = ["G"]'),
    ("block = 4\nguide = 6\nthrough = \"E\"\nangle = -20",
     "block = 4\nguide = 3\nthrough = \"G\"\nangle = 158"))

#: (2) class3-slider's block slides on the crank 1 (the line through E at -20° as drawn,
#: carried by the crank) instead of on the frame: the guide is a known moving link;
#: the crank rocks within about [-278°, -136°]
ON_CRANK = _drawing("class3-slider", NO_RANGE, ("guide = 6", "guide = 1"), PARTIAL)
#: (2) the same prismatic pair with its block and guide swapped (block 1, guide 4):
#: the same constraint (a crank's point at its drawn offset from a line fixed in 4)
ON_CRANK_SWAPPED = _drawing("class3-slider", NO_RANGE, ("block = 4\nguide = 6",
                                                        "block = 1\nguide = 4"), PARTIAL)
#: (2) class3-two-cranks with its rocker G-E a block at E sliding on the secondary
#: crank 7 (H-K, geared θ7 = −θ1 + phase)
ON_SECOND_CRANK = _drawing(
    "class3-two-cranks", PARTIAL,
    ("G = [188.83, 22.69]\n", ""), ('joints = ["G", "E"]', 'joints = ["E"]'),
    ("[[mechanism.driver]]\ntype = \"crank\"\nlink = 1",
     "[[mechanism.slider]]\nblock = 4\nguide = 7\nthrough = \"E\"\nangle = -20\n\n"
     "[[mechanism.driver]]\ntype = \"crank\"\nlink = 1"))

#: (3) a compound hinge inside a group: class4-group with its joints D and E merged into
#: D (on links 3, 4 and 5): link 4 is the binary G-D, link 5 the binary D-F; the group
#: (links 2 … 5, pairs B, G, C, F and D twice) has no dyad
COMPOUND = _drawing("class4-group", ("E = [106, 49]\n", ""),
                    ('joints = ["G", "D", "E"]', 'joints = ["G", "D"]'),
                    ('joints = ["E", "F"]', 'joints = ["D", "F"]'), PARTIAL)

#: (3) a compound hinge on a known joint: class3-slider's link 5 hung on the crank pin B
#: (on links 1, 2 and 5) instead of the frame pivot H
COMPOUND_OUTER = _drawing("class3-slider", NO_RANGE, ("H = [80.08, 150.21]\n", ""),
                          ('joints = ["H", "F"]', 'joints = ["B", "F"]'), PARTIAL)

#: (4) a block carrying two joints: class4-group's ternary link 4 (G, D, E) loses its
#: frame pivot G and slides on the frame along a line at -30° through D; both ends of
#: the drawn branch are dead points of the group
TWO_JOINT_BLOCK = _drawing(
    "class4-group", ("G = [150, 0]\n", ""),
    ('joints = ["G", "D", "E"]     # θ4: from the pivot G to D', 'joints = ["D", "E"]'),
    ("[[mechanism.driver]]",
     "[[mechanism.slider]]\nblock = 4\nguide = 6\nthrough = \"D\"\nangle = -30\n\n"
     "[[mechanism.driver]]"), PARTIAL)

#: (5) class3-slider's triad driven through a slider-crank: the crank 1 (A-D) and the
#: coupler 7 (D-K) drive the block 8 (K, B) along the frame's line y = -1.44 (an RRP
#: dyad), and the triad hangs on the block's joint B (the joints form has crank
#: drivers only: a block on the frame cannot be the driver itself)
SLIDER_CRANK = _drawing(
    "class3-slider", NO_RANGE,
    ("A = [0, 0]\n", "A = [0, 0]\nD = [-10, 15]\nK = [-40, -1.44]\n"),
    ('joints = ["A", "B"]',
     'joints = ["A", "D"]\n[[mechanism.link]]\nnumber = 7\njoints = ["D", "K"]\n'
     '[[mechanism.link]]\nnumber = 8\njoints = ["K", "B"]'),
    ("[[mechanism.driver]]",
     "[[mechanism.slider]]\nblock = 8\nguide = 6\nthrough = \"K\"\nangle = 0\n\n"
     "[[mechanism.driver]]"), PARTIAL)
#: (2) the same, the triad's block 4 sliding on the coupler 7 (an earlier group's link,
#: whose angle passes ±180° at θ1 ≈ -4.58° and 184.58°); the reference turns fully
ON_COUPLER = SLIDER_CRANK.replace("block = 4\nguide = 6", "block = 4\nguide = 7")

#: (name, drawing, crank angles [deg], the joints the Newton group solves)
CASES = [
    ("inner-slider", INNER_SLIDER, np.arange(0.0, 360.0, 20.0), "CF"),
    ("on-crank", ON_CRANK, np.arange(-270.0, -140.0, 15.0), "CEF"),
    ("on-second-crank", ON_SECOND_CRANK, np.arange(-265.0, -120.0, 15.0), "CEF"),
    ("compound-hinge", COMPOUND, np.arange(0.0, 360.0, 20.0), "CDF"),
    ("two-joint-block", TWO_JOINT_BLOCK, np.arange(-100.0, 221.0, 20.0), "CDEF"),
    ("compound-outer", COMPOUND_OUTER, np.arange(0.0, 360.0, 20.0), "CEF"),
    ("slider-crank", SLIDER_CRANK, np.arange(0.0, 360.0, 20.0), "KBCEF"),
    ("on-coupler-window", ON_COUPLER, np.arange(0.0, 181.0, 20.0), "CEF"),
]


def _write(tmp_path, text, name="case.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _engine_motion(spec, q):
    omega = spec.input.omega
    ins = {spec.input.driver: DriverMotion(q, omega, 0.0)}
    for k, (ratio, phase) in spec.input.followers.items():
        ins[k] = DriverMotion(ratio * q + phase, ratio * omega, 0.0)
    return solve(spec.linkage, ins)


def _assert_close(want, have, tol, what):
    err = np.max(np.abs(np.asarray(have) - np.asarray(want)))
    assert err <= tol * np.max(np.abs(want)), (what, err / np.max(np.abs(want)), tol)


def _against_reference(path, deg, joints, ref_path=None, slides=True):
    spec = load_kin_spec(path, ())
    assert any(isinstance(e, NewtonGroup) for e in spec.linkage.elements)
    q = np.radians(deg)
    m = _engine_motion(spec, q)
    assert m.regular.all()
    lk = REF.JointsLinkage(ref_path or path)
    ref = lk.motion(q)
    for j in joints:
        pm = m.points[j]
        got = (np.stack([pm.x, pm.y], -1), np.stack([pm.vx, pm.vy], -1),
               np.stack([pm.ax, pm.ay], -1))
        for want, have, tol, f in zip(ref[j], got, (1e-12, 1e-7, 1e-6), "pva"):
            _assert_close(want, have, tol, (j, f))
    if slides:
        # the slides s, v, a (from the drawn `through` point along the line as its guide
        # carries it), each the reference's slider between the same two links
        mine = {frozenset((sm.block, sm.guide)): sm for sm in m.slides.values()}
        for (blk, gd, _t, _a), want in zip(lk.sliders, lk.slide_motion(q)):
            sm = mine[frozenset((blk, gd))]
            for w, have, tol, f in zip(want, (sm.s, sm.v, sm.a), (1e-12, 1e-7, 1e-6), "sva"):
                _assert_close(w, have, tol, (sm.block, sm.guide, f))
    return spec, m


#: the decomposition of each case: its Newton-solved group's type and the mechanism's
#: class (the largest closed contour of inner pairs, docs/grashof.md)
STRUCTURE = {"inner-slider": ("triad", 3), "on-crank": ("triad", 3),
             "on-second-crank": ("triad", 3), "compound-hinge": ("group", 4),
             "two-joint-block": ("group", 4), "compound-outer": ("triad", 3),
             "slider-crank": ("triad", 3), "on-coupler-window": ("triad", 3)}


@pytest.mark.parametrize("name, text, deg, joints", CASES, ids=[c[0] for c in CASES])
def test_against_the_independent_solution(tmp_path, name, text, deg, joints):
    spec, _m = _against_reference(_write(tmp_path, text), deg, joints)
    group = next(e for e in spec.linkage.elements if isinstance(e, NewtonGroup))
    kind, cls = STRUCTURE[name]
    found = [g for g in spec.linkage.structure.groups if tuple(g.links) == group.links]
    assert [g.type for g in found] == [kind]
    assert spec.linkage.structure.mechanism_class == cls


def test_swapped_block_and_guide_is_the_same_motion(tmp_path):
    # (2) block 1 on guide 4 is the constraint of block 4 on guide 1: the joints are the
    # reference's for the unswapped drawing (its slide is measured from the other side)
    _against_reference(_write(tmp_path, ON_CRANK_SWAPPED), np.arange(-270.0, -140.0, 15.0),
                       "CEF", ref_path=_write(tmp_path, ON_CRANK, "ref.toml"), slides=False)


def test_dead_points_end_the_block_group_where_the_reference_ends(tmp_path):
    # (4) the two-joint block: mechcli's table ends at dead points on both sides of the
    # drawing; the reference's continuation reaches each to 1e-6 rad and no further
    path = _write(tmp_path, TWO_JOINT_BLOCK)
    group = next(e for e in load_kin_spec(path, ()).linkage.elements
                 if isinstance(e, NewtonGroup))
    assert group.period == 0.0
    lk = REF.JointsLinkage(path)
    for limit, sign in ((group.table[0][-1], 1.0), (group.table[0][0], -1.0)):
        u = lk.sweep([limit - sign * 1e-4])[0]
        u = lk.solve_at(limit - sign * 1e-6, u)
        with pytest.raises(RuntimeError):
            lk.solve_at(limit + sign * 1e-4, u)


FORCES = """
[[link]]
number = 2
mass = 2.0
J = 0.004
[[link]]
number = 3
mass = 1.0
J = 0.001
[[link]]
number = 4
mass = 3.0
J = 0.006
[[link]]
number = 5
mass = 1.0
J = 0.001
[gravity]
g = 9.81
[[load]]
name = "work"
link = {link}
force = [0, -200]
at = "{at}"
"""

#: (6) masses, gravity and a load on each case (in the crank's range where it rocks)
FORCE_CASES = [
    ("inner-slider", INNER_SLIDER, "", 3, "F"),
    ("on-crank", ON_CRANK, "start = -270\nstop = -140\n", 4, "E"),
    ("on-crank-swapped", ON_CRANK_SWAPPED, "start = -270\nstop = -140\n", 4, "E"),
    ("on-second-crank", ON_SECOND_CRANK, "start = -265\nstop = -120\n", 4, "E"),
    ("compound-hinge", COMPOUND, "", 4, "D"),
    ("two-joint-block", TWO_JOINT_BLOCK, "", 4, "E"),
    ("compound-outer", COMPOUND_OUTER, "", 4, "E"),
    ("slider-crank", SLIDER_CRANK, "", 4, "E"),
]


def _force(tmp_path, text, span, link, at, name="f.toml"):
    text = text.replace('command = "kin"', 'command = "force"')
    text = text.replace("[input]\n", "[input]\n" + span)
    return run_json("force", _write(tmp_path, text + FORCES.format(link=link, at=at), name),
                    "-q")["results"]


@pytest.mark.parametrize("name, text, span, link, at", FORCE_CASES,
                         ids=[c[0] for c in FORCE_CASES])
def test_kinetostatics_passes_the_power_balance(tmp_path, name, text, span, link, at):
    res = _force(tmp_path, text, span, link, at)
    assert res["positions"] > 100
    assert res["power_balance_residual"] < 1e-12
    assert res["force_balance_residual"] < 1e-12


def test_swapped_block_and_guide_need_the_same_torque(tmp_path):
    # (6) the statics' block/guide roles: the same constraint drawn either way round
    # needs the same balancing torque and pin forces (the pair's own moment MR is
    # referred to a different point of the block, so it differs)
    a = _force(tmp_path, ON_CRANK, "start = -270\nstop = -140\n", 4, "E", "a.toml")
    b = _force(tmp_path, ON_CRANK_SWAPPED, "start = -270\nstop = -140\n", 4, "E", "b.toml")
    for key in ("Mb_max_N_m", "Mb_min_N_m", "FR12_max_N", "FR23_max_N", "FR35_max_N",
                "FR56_max_N", "FR16_max_N", "FR14_max_N"):
        assert b[key] == pytest.approx(a[key], rel=1e-9), key


# -- bad drawings -------------------------------------------------------------------
def _at_dead_point():
    """class3-slider with its line of sliding turned so that the triad is drawn at its
    dead point: the normal to the line at E passes through the intersection O of the
    lines B-C and H-F (the three legs' lines concurrent: the ternary link can turn about
    O to first order)."""
    B, C, F, H = (np.array(v) for v in ([-19.35, -1.44], [81.65, 53.48], [102.9, 93.53],
                                         [80.08, 150.21]))
    E = np.array([117.78, 50.71])
    t = np.linalg.solve(np.array([C - B, H - F]).T, H - B)
    O = B + t[0] * (C - B)
    angle = math.degrees(math.atan2(O[1] - E[1], O[0] - E[0])) + 90.0
    return _drawing("class3-slider", NO_RANGE, ("angle = -20", f"angle = {angle!r}"))


def test_a_group_drawn_at_its_dead_point_is_exit_2(tmp_path):
    # (7) one line, exit 2, no traceback, no NaN in the JSON
    path = _write(tmp_path, _at_dead_point())
    proc = run_inprocess("kin", path, "-q", "--no-plot", "-o", tmp_path / "out")
    assert proc.returncode == 2
    assert "nan" not in one_line_error(proc).lower()
    proc = run_inprocess("kin", path, "--json", "--no-plot")
    assert proc.returncode == 2 and "NaN" not in proc.stdout
    assert json.loads(proc.stdout)["exit_code"] == 2


def test_a_group_drawn_at_its_dead_point_says_so(tmp_path):
    proc = run_inprocess("kin", _write(tmp_path, _at_dead_point()), "-q", "--no-plot",
                         "-o", tmp_path / "out")
    line = one_line_error(proc)
    assert "dead point" in line and "does not close" not in line


def test_a_guide_on_the_crank_is_read_a_turn_away(tmp_path):
    # (2) ON_CRANK at θ1 and θ1 + 360°: the same position (the reference: the same q)
    spec = load_kin_spec(_write(tmp_path, ON_CRANK), ())
    q = np.radians(np.arange(-270.0, -140.0, 15.0))
    a, b = _engine_motion(spec, q), _engine_motion(spec, q + 2 * np.pi)
    assert b.regular.all()
    for j in "CEF":
        _assert_close(a.points[j].x, b.points[j].x, 1e-12, j)


def test_a_guide_on_a_dyad_link_turns_fully(tmp_path):
    _against_reference(_write(tmp_path, ON_COUPLER), np.arange(0.0, 360.0, 20.0), "CEF")


def test_a_group_drawn_at_its_limit_of_assembly_sweeps_one_way(tmp_path):
    # (7) the two-joint block drawn where its branch ends (the dead point located above
    # at θ1 = 222.76290083676577°, which the reference confirms): the drawing builds,
    # the sweep stops at the drawn crank angle (exit 3 naming it, one line), and with
    # partial = true the rest of the branch is analysed, no NaN in the JSON
    drawn = {"B": "[-7.341696506363567, -6.78966069906656]",
             "C": "[27.35835334791489, 94.24947300718901]",
             "D": "[60.179809914541394, 89.80515204122918]",
             "E": "[49.17980991457768, 81.80515204122426]",
             "F": "[48.62103536938662, 28.55397580035007]"}
    text = TWO_JOINT_BLOCK.replace("partial = true\n", "").replace("step = 1\n", "step = 4\n")
    for line in text.splitlines():
        if line[:1] in drawn and line[1:4] == " = ":
            text = text.replace(line, f"{line[0]} = {drawn[line[0]]}")
    q_drawn = math.degrees(math.atan2(-6.78966069906656, -7.341696506363567)) + 360.0
    proc = run_inprocess("kin", _write(tmp_path, text), "-q", "--no-plot", "-o",
                         tmp_path / "out")
    assert proc.returncode == 3
    assert f"θ1 = {q_drawn:.4f}°" in one_line_error(proc)
    path = _write(tmp_path, text.replace("step = 4\n", "step = 4\npartial = true\n"), "p.toml")
    proc = run_inprocess("kin", path, "-q", "--json", "--no-plot")
    assert proc.returncode == 0 and "NaN" not in proc.stdout
    assert json.loads(proc.stdout)["results"]["positions"] > 75


def test_a_periodic_table_with_shorter_steps_covers_the_turn():
    # a synthetic branch (hand-made: its pose is (r cos q, r sin q, q)) whose Newton
    # fails over 0.3° steps for 1 < q < 1.2 rad, so the march halves its steps there
    from mechcli.core.linkage.newton_group import TABLE_STEP, table_from_marches

    def advance(m, i, prev):
        q = float(m[i])
        if 1.0 < q < 1.2 and abs(q - prev[2]) > math.radians(0.3):
            return None
        return (0.01 * math.cos(q), 0.01 * math.sin(q), q)

    table, period = table_from_marches(lambda q: np.asarray(q, dtype=float), advance, 0.0,
                                       (0.01, 0.0, 0.0), 0.02)
    assert period == pytest.approx(2 * math.pi)
    assert table[0][-1] == pytest.approx(2 * math.pi - TABLE_STEP, abs=1e-12)


def test_a_secondary_crank_at_half_speed_is_read_on_its_own_turn(tmp_path):
    # class3-two-cranks with θ7 = θ1/2 + phase: the known part repeats only every two
    # turns of θ1.  The drawn branch ends at a dead point at θ1 ≈ -170.83° (the reference
    # fails there too) and runs back over a turn, so the table is one window
    # [-530.83°, -170.83°].  θ1 = 190 … 350° is the window's θ1 − 720° (the same θ7 mod
    # 360°): the reference continued to θ1 − 720°; θ1 = 0 … 180° would be the window's
    # θ1 − 360°, where θ7 differs by 180° (not reached on the drawn branch): unassembled
    text = _drawing("class3-two-cranks", PARTIAL, ("ratio = -1 ", "ratio = 0.5 "))
    path = _write(tmp_path, text)
    spec = load_kin_spec(path, ())
    assert not _engine_motion(spec, np.radians(np.arange(0.0, 181.0, 20.0))).regular.any()
    q = np.radians(np.arange(190.0, 360.0, 20.0))
    m = _engine_motion(spec, q)
    assert m.regular.all()
    ref = REF.JointsLinkage(path).motion(q - 4 * np.pi)
    for j in "CEF":
        pm = m.points[j]
        got = (np.stack([pm.x, pm.y], -1), np.stack([pm.vx, pm.vy], -1),
               np.stack([pm.ax, pm.ay], -1))
        for want, have, tol, f in zip(ref[j], got, (1e-12, 1e-7, 1e-6), "pva"):
            _assert_close(want, have, tol, (j, f))
