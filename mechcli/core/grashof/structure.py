"""Structural analysis (杆组分解): a mechanism's drivers and Assur groups.

Pure Python, like :mod:`.mobility`: a mechanism is a short list of joints.

A mechanism of mobility F is its frame, F drivers (each joined to the frame by
one lower pair) and Assur groups (基本杆组): chains of n links and p lower
pairs with 3n = 2p, none of which contains a smaller such chain.  They are
found in solving order: each group's outer pairs join links already known (the
frame, the drivers, earlier groups), so solving the groups in order positions
the whole mechanism.  The decomposition of a mechanism whose groups are all
dyads (n = 2, p = 3) is unique; a class-III triad (a ternary link held by
three binary links: n = 4, p = 6) cannot be split into dyads.

Classes (the book's convention, after 机械原理 textbooks): a group's class is
the number of sides of the largest closed contour its inner pairs form — a
dyad (one inner pair) is class II, a triad (a ternary link whose three inner
pairs form a triangle) class III, four links closing a quadrilateral of inner
pairs class IV; the mechanism's class is that of its highest group.
"""

from __future__ import annotations

from itertools import combinations
from typing import Collection, Dict, Iterable, List, Optional, Sequence, Set, Tuple

from mechcli.core.grashof.mobility import LOWER, Joint, MobilityError
from mechcli.core.records import record

#: the largest group searched for (links); every textbook group has at most 6
MAX_GROUP = 6


@record
class Group:
    """One Assur group (or a driver) of a decomposition.

    Attributes
    ----------
    type : str
        ``driver``; a dyad's pairs in order (outer, inner, outer: ``RRR``,
        ``RRP``, ``RPR``, ``PRP``, ``RPP``); ``triad`` (class III);
        ``group`` otherwise.
    klass : int
        1 for a driver, 2 for a dyad, 3 for a triad, ... (JSON ``class``).
    links : tuple of int
        The group's links (for a dyad, in the order of its ``type``).
    joints : tuple of str
        Its pairs' names: the outer pairs (to known links) and the inner ones.
    """

    type: str
    klass: int
    links: tuple
    joints: tuple


@record
class Structure:
    """A decomposition: drivers first, then the groups in solving order.

    Attributes
    ----------
    groups : tuple of Group
    mechanism_class : int
        The highest group's class (1 for a driver and frame alone).
    """

    groups: tuple
    mechanism_class: int


def decompose(joints: Iterable[Joint], frame: int, drivers: Iterable[int]) -> Structure:
    """Decompose a mechanism into its drivers and Assur groups.

    Parameters
    ----------
    joints : sequence of :class:`~.mobility.Joint`
        Every lower pair (``R``, ``P``); a revolute joining m links is a
        compound hinge (m − 1 pairs).
    frame : int
        The fixed link's number.
    drivers : sequence of int
        The driving links, each joined to the frame by one pair.

    Returns
    -------
    Structure

    Raises
    ------
    MobilityError
        A driver not joined to the frame, a higher pair, or links that no
        group of at most :data:`MAX_GROUP` links can position (the mechanism
        has more freedoms than drivers, or a part of it is over-constrained).
    """
    joints = tuple(joints)
    for j in joints:
        if j.kind not in LOWER:
            raise MobilityError(f"joint {j.name or j.kind}: the structural analysis takes "
                                f"lower pairs (R, P) only, got {j.kind}")
    links = sorted({k for j in joints for k in j.links} - {frame})
    known = {frame}
    groups = []
    for d in drivers:
        pair = [j for j in joints if frame in j.links and d in j.links]
        if d == frame or d not in links or not pair:
            raise MobilityError(f"driver {d} is not joined to the frame {frame}")
        known.add(d)
        groups.append(Group("driver", 1, (d,), (pair[0].name,)))
    unknown = [k for k in links if k not in known]
    while unknown:
        found = _next_group(joints, known, unknown)
        if found is None:
            raise MobilityError(
                f"links {unknown} form no Assur group on the known links {sorted(known)} "
                f"(more freedoms than drivers, or over-constrained)")
        groups.append(found)
        known.update(found.links)
        unknown = [k for k in unknown if k not in known]
    return Structure(tuple(groups), max(g.klass for g in groups))


def _pairs(joints: Sequence[Joint], group: Sequence[int],
           known: Collection[int]
           ) -> Tuple[List[Tuple[Joint, List[int]]], List[Tuple[Joint, List[int]]]]:
    """The pairs that join the links of *group* to each other and to *known*
    links: ``(outer, inner)`` lists of ``(joint, links of the group there)``."""
    outer, inner = [], []
    for j in joints:
        here = [k for k in j.links if k in group]
        if not here:
            continue
        if any(k in known for k in j.links):
            outer.append((j, here))
        elif len(here) > 1:
            inner.append((j, here))
    return outer, inner


def _count(outer: List[Tuple[Joint, List[int]]], inner: List[Tuple[Joint, List[int]]]) -> int:
    # an outer hinge fixes every group link at it to a known link; an inner one
    # joining m group links makes m - 1 pairs
    return sum(len(h) for _, h in outer) + sum(len(h) - 1 for _, h in inner)


def _connected(group: Sequence[int], inner: List[Tuple[Joint, List[int]]]) -> bool:
    group = list(group)
    seen, todo = {group[0]}, [group[0]]
    while todo:
        k = todo.pop()
        for _, here in inner:
            if k in here:
                for m in here:
                    if m not in seen:
                        seen.add(m)
                        todo.append(m)
    return len(seen) == len(group)


def _next_group(joints: Sequence[Joint], known: Collection[int],
                unknown: Sequence[int]) -> Optional[Group]:
    """The smallest Assur group on the known links (the first by link number)."""
    for n in range(2, min(MAX_GROUP, len(unknown)) + 1, 2):
        for group in combinations(unknown, n):
            outer, inner = _pairs(joints, group, known)
            if 3 * n != 2 * _count(outer, inner) or not outer or not _connected(group, inner):
                continue
            # an Assur group contains no smaller one (those were searched first)
            return _describe(group, outer, inner)
    return None


def _describe(group: Sequence[int], outer: List[Tuple[Joint, List[int]]],
              inner: List[Tuple[Joint, List[int]]]) -> Group:
    names = tuple(j.name for j, _ in outer) + tuple(j.name for j, _ in inner)
    a_outer = [j for j, h in outer if group[0] in h]
    b_outer = [j for j, h in outer if group[-1] in h]
    if len(group) == 2 and len(inner) == 1 and len(a_outer) == len(b_outer) == 1:
        (ji, _), = inner
        (a, b), oa, ob = group, a_outer[0], b_outer[0]
        kinds = oa.kind + ji.kind + ob.kind
        if kinds == "PRR":   # RRP read from its other end
            kinds, (a, b), (oa, ob) = "RRP", (b, a), (ob, oa)
        elif kinds == "PPR":
            kinds, (a, b), (oa, ob) = "RPP", (b, a), (ob, oa)
        return Group(kinds, 2, (a, b), (oa.name, ji.name, ob.name))
    klass = _klass(group, inner)
    kind = "triad" if klass == 3 and len(group) == 4 else "group"
    return Group(kind, klass, tuple(group), names)


def _klass(group: Sequence[int], inner: List[Tuple[Joint, List[int]]]) -> int:
    """The number of sides of the largest closed contour of inner pairs: the
    inner pairs on one link (a ternary link's three make a triangle), or a
    cycle of links joined by inner pairs."""
    on_link = {k: sum(1 for _, h in inner if k in h) for k in group}
    best = max(on_link.values())
    adj: Dict[int, Set[int]] = {k: set() for k in group}
    for _, here in inner:
        for a, b in combinations(here, 2):
            adj[a].add(b)
            adj[b].add(a)

    def longest_cycle(start: int, node: int, seen: Set[int]) -> int:
        best_len = 0
        for m in adj[node]:
            if m == start and len(seen) >= 3:
                best_len = max(best_len, len(seen))
            elif m not in seen and m > start:
                best_len = max(best_len, longest_cycle(start, m, seen | {m}))
        return best_len

    for k in group:
        best = max(best, longest_cycle(k, k, {k}))
    return max(2, best)
