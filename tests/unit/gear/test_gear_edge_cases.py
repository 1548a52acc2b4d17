"""``mechcli gear`` edge cases: no addendum, tip inside the base circle, the book's
inverse-involute start, internal interference at the ring tip, thin teeth, pointed teeth."""

import math

import pytest

from mechcli.core.gear.spur import GearGeometryError, spur_gear
from tests.conftest import run_inprocess


def _spec(tmp_path, body):
    path = tmp_path / "g.toml"
    path.write_text('command = "gear"\nunits = "mm"\n' + body, encoding="utf-8")
    return path


def test_x_min_without_addendum():
    # x_min = ha* - z sin^2(alpha) / 2; ha* = 0 divided by z_min = 0 (ZeroDivisionError, exit 1)
    g = spur_gear(20, 1e-3, math.radians(20), ha_star=0.0)
    assert g.x_min == pytest.approx(-10 * math.sin(math.radians(20)) ** 2, rel=1e-15)
    g = spur_gear(12, 1e-3, math.radians(20))
    assert g.x_min == pytest.approx((17.0973 - 12) / 17.0973, abs=1e-5)   # (zmin - z)/zmin


def test_spur_without_addendum_runs(tmp_path):
    proc = run_inprocess("gear", _spec(tmp_path, "[spur]\nz = 20\nm = 1\nha_star = 0\nc_star = 0\n"),
                   "--no-plot", "-q", "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr


def test_tip_circle_inside_base_circle_is_unsolvable(tmp_path):
    # z = 7, x = -1.5, alpha = 30: ra = 3.0 m < rb = 3.03 m; the pair died in acos (exit 1)
    with pytest.raises(GearGeometryError, match="inside the base circle"):
        spur_gear(7, 1.0, math.radians(30), x=-1.5)
    proc = run_inprocess("gear", _spec(tmp_path, "[pair]\nz1 = 7\nz2 = 40\nm = 1\nalpha_deg = 30\n"
                                           "x1 = -1.5\nx2 = 1.5\n"),
                   "--no-plot", "-q", "--out", tmp_path / "o")
    assert proc.returncode == 3, proc.stderr
    assert "inside the base circle" in proc.stderr


@pytest.mark.parametrize("start", ["1.6", "0", "-0.5"])
def test_book_start_outside_the_quadrant_is_a_spec_error(tmp_path, start):
    # was exit 3 with "its first step passes pi/2 for theta > 1.0468" (true only for 0.8)
    body = f'[inverse_involute]\ntheta = 0.02\nmethod = "book"\nbook_start = {start}\n'
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "-q", "--out", tmp_path / "o")
    assert proc.returncode == 2, proc.stderr
    assert "book_start" in proc.stderr


def test_book_start_failure_message_only_claims_the_limit_for_0_8():
    from mechcli.core.errors import ConvergenceError
    from mechcli.core.gear.involute import inverse_involute, inverse_involute_scalar
    with pytest.raises(ConvergenceError, match="theta > 1.0468"):
        inverse_involute_scalar(1.05, "book")
    with pytest.raises(ConvergenceError, match=r"theta > 1.0468"):
        inverse_involute([0.5, 1.05], "book")
    with pytest.raises(ConvergenceError) as err:
        inverse_involute_scalar(0.02, "book", start=1.6)
    assert "1.0468" not in str(err.value)


@pytest.mark.parametrize("z1, z2, expected", [(20, 100, False), (20, 60, True), (17, 80, True)])
def test_internal_interference_uses_the_ring_tip(z1, z2, expected):
    # The ring's tip circle cuts the line of action sqrt(ra2^2 - rb2^2) from N2; it meets the
    # pinion above its base circle iff that reaches N1 (N1N2 = a' sin a').  The pinion's tip
    # reach was tested instead: z2 = 100 (27.817 > 27.362 mm, no interference) was flagged.
    from mechcli.core.gear.pair import gear_pair
    alpha = math.radians(20)
    g1 = spur_gear(z1, 2.0, alpha)
    g2 = spur_gear(z2, 2.0, alpha, internal=True)
    pair = gear_pair(g1, g2, a_w=z2 - z1)
    reach2 = math.sqrt(g2.ra ** 2 - g2.rb ** 2)
    assert (reach2 < (z2 - z1) * math.sin(alpha)) is expected
    assert pair.interference is expected


def test_thin_teeth_without_zero_backlash_mount_at_a_given_distance(tmp_path):
    # z = 12 + 30, x1 = x2 = -0.5: inv alpha' = 2 tan 20° (-1)/42 + inv 20° < 0, so no a' gives
    # zero backlash and no a' jams.  A given a' = 20 mm (> rb1 + rb2 = 19.73) was refused
    # (exit 3, "no zero-backlash pressure angle exists"); independent: j = 2 pi r1'/z1 - s1' - s2'.
    from mechcli.core.gear.pair import gear_pair, zero_backlash_distance
    alpha = math.radians(20)
    g1 = spur_gear(12, 1.0, alpha, x=-0.5)
    g2 = spur_gear(30, 1.0, alpha, x=-0.5)
    assert zero_backlash_distance(g1, g2) is None
    pair = gear_pair(g1, g2, a_w=20.0)
    aw = math.acos(21 * math.cos(alpha) / 20)
    inv = math.tan(aw) - aw - (math.tan(alpha) - alpha)
    r1, r2 = g1.rb / math.cos(aw), g2.rb / math.cos(aw)
    s1 = r1 * (g1.s / g1.r - 2 * inv)
    s2 = r2 * (g2.s / g2.r - 2 * inv)
    assert pair.backlash == pytest.approx(2 * math.pi * r1 / 12 - s1 - s2, rel=1e-12)
    assert pair.backlash > 0
    body = "[pair]\nz1 = 12\nz2 = 30\nm = 1\nx1 = -0.5\nx2 = -0.5\n"
    proc = run_inprocess("gear", _spec(tmp_path, body + "a_w = 20\n"), "--json", "--no-plot",
                   "--out", tmp_path / "o")
    assert proc.returncode == 0, proc.stderr
    proc = run_inprocess("gear", _spec(tmp_path, body + "a_w = 19.7\n"), "--no-plot", "-q",
                   "--out", tmp_path / "o")
    assert proc.returncode == 2 and "a_w" in proc.stderr and "base circles" in proc.stderr
    proc = run_inprocess("gear", _spec(tmp_path, body), "--no-plot", "-q", "--out", tmp_path / "o")
    assert proc.returncode == 3 and "zero-backlash" in proc.stderr


def test_contact_ratio_stops_where_a_pointed_tooth_ends():
    """z1 = 5, x1 = 1, alpha = 14.5°: the pinion's flanks meet at 4.0855 mm, below
    its tip circle ra = 4.5 mm; the contact (and epsilon_alpha) must stop there."""
    import math

    from mechcli.core.gear.spur import spur_gear
    from mechcli.core.gear.pair import gear_pair

    g1 = spur_gear(5, 1.0, math.radians(14.5), x=1.0)
    g2 = spur_gear(40, 1.0, math.radians(14.5))
    assert g1.pointed_radius < g1.ra
    pair = gear_pair(g1, g2)
    t = math.tan(pair.alpha_w)
    tan_p = math.sqrt(g1.pointed_radius ** 2 - g1.rb ** 2) / g1.rb
    expected = (5 * (tan_p - t) + 40 * (math.tan(g2.alpha_a) - t)) / (2 * math.pi)
    assert pair.epsilon_alpha == pytest.approx(expected, rel=1e-12)
    naive = (5 * (math.tan(g1.alpha_a) - t) + 40 * (math.tan(g2.alpha_a) - t)) / (2 * math.pi)
    assert pair.epsilon_alpha < naive - 0.05
