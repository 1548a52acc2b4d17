"""Mobility (degrees of freedom) of a planar mechanism: F = 3n − 2P_L − P_H.

Pure Python (no numpy needed): a mechanism is a short list of joints.
"""

from __future__ import annotations

from typing import Iterable, Set

from mechcli.core.records import record

LOWER = ("R", "P")
HIGHER = ("H",)


@record
class Joint:
    """One joint of a mechanism.

    Attributes
    ----------
    kind : str
        ``R`` revolute, ``P`` prismatic (lower pairs), ``H`` higher pair
        (cam or gear contact).
    links : tuple of int
        The links meeting at the joint (the frame included by its number).
    name : str
        Label for the explanation (e.g. ``B``).
    """

    kind: str
    links: tuple
    name: str = ""

    @property
    def pairs(self) -> int:
        """Pairs this joint counts: m − 1 for m links at a lower pair, 1 for a higher pair."""
        return 1 if self.kind in HIGHER else len(self.links) - 1


@record
class Mobility:
    """Result of the Grübler count.

    Attributes
    ----------
    F : int
        Degrees of freedom 3n − 2P_L − P_H − F' + p'.
    n : int
        Moving links.
    moving : tuple of int
        Their numbers.
    frame : int
        The frame's number.
    P_L, P_H : int
        Lower and higher pairs (compound hinges counted m − 1).
    local_dof : int
        F' (e.g. a roller turning about its own pin), subtracted.
    redundant : int
        p' redundant (passive) constraints, added back.
    joints : tuple of Joint
    structure : Structure or None
        The drivers and Assur groups (:func:`.structure.decompose`), when the
        drivers are known.
    """

    F: int
    n: int
    moving: tuple
    frame: int
    P_L: int
    P_H: int
    local_dof: int
    redundant: int
    joints: tuple
    structure: object = None


class MobilityError(ValueError):
    """A joint list that does not describe a mechanism."""


def count_mobility(joints: Iterable[Joint], frame: int, local_dof: int = 0,
                   redundant: int = 0) -> Mobility:
    """Degrees of freedom of a planar mechanism by the Grübler–Kutzbach count.

    Parameters
    ----------
    joints : sequence of Joint
        Every joint; a revolute joining m links is one compound hinge.
    frame : int
        Number of the fixed link.
    local_dof : int
        Local (passive) degrees of freedom, such as a follower roller.
    redundant : int
        Redundant constraints (虚约束) declared by the user.

    Returns
    -------
    Mobility

    Raises
    ------
    MobilityError
        A lower pair with fewer than 2 links, a higher pair not joining
        exactly 2, a link joined to itself, or a frame that no joint names.

    Notes
    -----
    F = 3n − 2P_L − P_H with n moving links, every lower pair removing two
    and every higher pair one of the 3 planar freedoms of a link; m links at
    one hinge make m − 1 pairs; local freedoms are subtracted and redundant
    constraints added back: F = 3n − (2P_L + P_H − p') − F'.
    """
    joints = tuple(joints)
    links: Set[int] = set()
    for j in joints:
        if len(set(j.links)) != len(j.links):
            raise MobilityError(f"joint {j.name or j.kind} lists a link twice: {list(j.links)}")
        if j.kind in HIGHER and len(j.links) != 2:
            raise MobilityError(f"higher pair {j.name or ''} must join exactly 2 links, "
                                f"got {list(j.links)}")
        if len(j.links) < 2:
            raise MobilityError(f"joint {j.name or j.kind} must join at least 2 links")
        links.update(j.links)
    if frame not in links:
        raise MobilityError(f"the frame {frame} is not joined by any joint "
                            f"(links: {sorted(links)})")
    moving = tuple(sorted(links - {frame}))
    p_l = sum(j.pairs for j in joints if j.kind in LOWER)
    p_h = sum(j.pairs for j in joints if j.kind in HIGHER)
    n = len(moving)
    F = 3 * n - 2 * p_l - p_h - local_dof + redundant
    return Mobility(F=F, n=n, moving=moving, frame=frame, P_L=p_l, P_H=p_h,
                    local_dof=local_dof, redundant=redundant, joints=joints)
