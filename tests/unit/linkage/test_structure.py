"""Structural analysis (杆组分解, issue 30 §2): drivers and Assur groups in solving order,
each group's type and class, against decompositions done by hand (3n = 2p for every group,
the class from the largest closed contour of inner pairs)."""

import pytest

from mechcli.core.grashof.mobility import Joint, MobilityError, count_mobility
from mechcli.core.grashof.structure import decompose


def R(name, *links):
    return Joint("R", links, name)


def P(name, *links):
    return Joint("P", links, name)


def _groups(joints, frame, drivers):
    st = decompose(joints, frame, drivers)
    return st.mechanism_class, [(g.type, g.klass, g.links, g.joints) for g in st.groups]


FOUR_BAR = [R("A", 4, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 4)]
# a crank 1 drives the ternary link 3 through 2; 3 is held by the rockers 4 (E-G), 5 (F-H)
TRIAD = [R("A", 6, 1), R("B", 1, 2), R("C", 2, 3), R("E", 3, 4), R("F", 3, 5),
         R("G", 4, 6), R("H", 5, 6)]


def test_four_bar_is_a_driver_and_an_rrr_dyad():
    assert _groups(FOUR_BAR, 4, [1]) == (2, [("driver", 1, (1,), ("A",)),
                                             ("RRR", 2, (2, 3), ("B", "C", "D"))])


def test_slider_crank_and_guide_bar_dyads_read_from_their_outer_pairs():
    slider = [R("A", 4, 1), R("B", 1, 2), R("C", 2, 3), P("P", 3, 4)]
    assert _groups(slider, 4, [1])[1][1] == ("RRP", 2, (2, 3), ("B", "C", "P"))
    # the same dyad written with the slider first is still RRP, from B's side
    flipped = [R("A", 4, 1), R("B", 1, 3), R("C", 3, 2), P("P", 2, 4)]
    assert _groups(flipped, 4, [1])[1][1] == ("RRP", 2, (3, 2), ("B", "C", "P"))
    # the shaper (例 1-4): block 2 on the guide bar 3 (RPR), then rod 4 and ram 5 (RRP)
    shaper = [R("A", 6, 1), R("B", 1, 2), P("B'", 2, 3), R("C", 3, 6), R("D", 3, 4),
              R("E", 4, 5), P("F", 5, 6)]
    assert _groups(shaper, 6, [1]) == (2, [("driver", 1, (1,), ("A",)),
                                           ("RPR", 2, (2, 3), ("B", "B'", "C")),
                                           ("RRP", 2, (4, 5), ("D", "E", "F"))])


def test_watt_and_stephenson_six_bars_are_two_dyads():
    # Watt: the four-bar's rocker 3 is ternary (C, D, E) and carries the second dyad 4-5
    watt = [R("A", 6, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 6), R("E", 3, 4),
            R("F", 4, 5), R("G", 5, 6)]
    assert _groups(watt, 6, [1])[1][1:] == [("RRR", 2, (2, 3), ("B", "C", "D")),
                                            ("RRR", 2, (4, 5), ("E", "F", "G"))]
    # Stephenson: the coupler 2 is ternary (B, C, E)
    steph = [R("A", 6, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 6), R("E", 2, 4),
             R("F", 4, 5), R("G", 5, 6)]
    assert _groups(steph, 6, [1])[1][2] == ("RRR", 2, (4, 5), ("E", "F", "G"))


def test_a_triad_is_class_three_and_its_class_depends_on_the_driver():
    # n = 4 links (2 ... 5), p = 6 pairs: 3n = 2p; no two of them form a dyad
    assert count_mobility(TRIAD, 6).F == 1
    klass, groups = _groups(TRIAD, 6, [1])
    assert klass == 3
    assert groups[1] == ("triad", 3, (2, 3, 4, 5), ("B", "G", "H", "C", "E", "F"))
    # driven by the rocker 4 the same chain is two dyads: 3-5 on E and H, then 1-2
    klass, groups = _groups(TRIAD, 6, [4])
    assert klass == 2
    assert [g[2] for g in groups[1:]] == [(3, 5), (1, 2)]


def test_a_closed_quadrilateral_of_inner_pairs_is_class_four():
    # links 2, 3, 4, 5 joined in a ring by inner pairs; 2 and 4 each with one outer pair:
    # n = 4, p = 4 + 2 = 6
    ring = [R("A", 7, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 4), R("E", 4, 5), R("F", 5, 2),
            R("G", 4, 7)]
    klass, groups = _groups(ring, 7, [1])
    assert (klass, groups[1][:3]) == (4, ("group", 4, (2, 3, 4, 5)))


def test_a_compound_hinge_counts_each_link_it_holds():
    # C joins 2, 3 and 4 (two pairs): 2-3 is a dyad on B and D, then 4-5 hangs on C
    joints = [R("A", 6, 1), R("B", 1, 2), R("C", 2, 3, 4), R("D", 3, 6), R("E", 4, 5),
              P("slide", 5, 6)]
    assert _groups(joints, 6, [1])[1][1:] == [("RRR", 2, (2, 3), ("B", "C", "D")),
                                              ("RRP", 2, (4, 5), ("C", "E", "slide"))]


def test_two_drivers_of_a_five_bar():
    five = [R("A", 5, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 4), R("E", 4, 5)]
    assert _groups(five, 5, [1, 4])[1] == [("driver", 1, (1,), ("A",)),
                                           ("driver", 1, (4,), ("E",)),
                                           ("RRR", 2, (2, 3), ("B", "C", "D"))]


def test_no_group_or_a_driver_off_the_frame_is_an_error_naming_the_links():
    with pytest.raises(MobilityError, match="driver 2 is not joined to the frame"):
        decompose(FOUR_BAR, 4, [2])
    # a five-bar with one driver has a freedom left: no Assur group positions 2, 3, 4
    five = [R("A", 5, 1), R("B", 1, 2), R("C", 2, 3), R("D", 3, 4), R("E", 4, 5)]
    with pytest.raises(MobilityError, match=r"links \[2, 3, 4\] form no Assur group"):
        decompose(five, 5, [1])
