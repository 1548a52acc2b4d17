"""The digits-lost estimate (docs/accuracy.md §1): how much each solved thing
amplifies rounding (:func:`amplification`, from each group's condition along the solving
order) and the correct significant digits of every quantity (:func:`estimate_accuracy`)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any, Dict, Sequence

import numpy as np

from mechcli.core.linkage.engine import Linkage, LinkageMotion, solve
from mechcli.core.linkage.sweep import _take
from mechcli.core.numerics import true_runs
from mechcli.core.records import record
from mechcli.core.types import FloatOrArray

if TYPE_CHECKING:
    from mechcli.core.linkage.sweep import Sweep

# ---------------------------------------------------------------------------
# accuracy: how many digits the float64 solution keeps near a singular position
# ---------------------------------------------------------------------------
#: the rounding unit of float64 (2.2e-16): one operation's relative error
EPS = float(np.finfo(float).eps)
#: the most significant digits a float64 result can have, -log10(EPS)
FULL_DIGITS = -np.log10(EPS)
#: the classes the estimate reports, by derivative order (the force solve is "forces")
ACCURACY_CLASSES = ("positions", "velocities", "accelerations")
#: warn when fewer correct significant digits than this remain (``[output] accuracy_warn``)
ACCURACY_WARN = 8.0
#: error model (see docs/accuracy.md): the error of a quantity of derivative order k
#: is ``C[k] * EPS * kappa**(k + 1)`` times its natural scale (1 rad or the linkage's
#: scale L, times omega1**k, with alpha1 added for k = 2), where kappa is the product
#: of 1/sin(gamma) of the dyads it depends on.  C is calibrated against a 60-digit
#: mpmath reference of a four-bar at 1e-3 ... 1e-13 from its change point
#: (tests/unit/linkage/test_accuracy_estimate.py): the estimate of the worst position is
#: within 0.2 digits of the true loss there (without C it was 0.6 digits optimistic).
ACCURACY_C = (4.0, 1.0, 3.0)
#: a result below this fraction of its natural magnitude (:func:`natural_scales`) is
#: round-off: 1e4 EPS, four digits of headroom over double precision for the amplification
#: κ^(k+1) of a quantity of order k near a singular position (an acceleration's noise
#: reaches it at κ ≈ 15).  Nearer a singular position the noise shows, with the digits
#: warning that says so; a real value this small against ω² is not taken for noise (an α
#: of 1e-6 rad/s² beside ω = 100 rad/s is 1e-10 of ω², above the floor)
NOISE_REL = 1e4 * EPS

_ORDER_OF_KIND = {"angle": 0, "length": 0, "angvel": 1, "velocity": 1, "angacc": 2,
                  "acceleration": 2}


@record
class AccuracyRange:
    """A continuous range of inputs where a class keeps fewer digits than asked:
    ``digits`` the fewest there (by ``symbol``, at input ``at``), ``start``/``stop``
    the inputs of the range [rad or m]."""

    quantity: str
    start: float
    stop: float
    digits: float
    symbol: str
    at: float


@record
class Accuracy:
    """Estimated correct significant digits, per position and per quantity.

    The digits count relative to the quantity's largest magnitude over the
    analysed range (so a value passing through zero does not "lose" digits).

    Attributes
    ----------
    q : ndarray
        Inputs where the estimate was made: the output rows and the refined
        near-dead positions (sorted).
    segment : ndarray of int
        Continuous arc (run) of every input; a range never crosses a gap.
    digits : dict
        Class (``positions``, ``velocities``, ``accelerations``, ``forces``) ->
        per-input fewest digits of its quantities.
    worst : dict
        Class -> per-input symbol of the quantity with those fewest digits.
    by_quantity : dict
        Symbol -> fewest digits over the range.
    """

    q: np.ndarray
    segment: np.ndarray
    digits: Dict[str, np.ndarray]
    worst: Dict[str, np.ndarray]
    by_quantity: Dict[str, float]

    def minimum(self):
        """Class -> fewest estimated digits over the range (0 ... 15.7)."""
        return {k: float(np.min(v)) for k, v in self.digits.items() if np.size(v)}

    def ranges(self, threshold: FloatOrArray = ACCURACY_WARN):
        """Every continuous range of inputs where a class keeps fewer than
        ``threshold`` digits: one :class:`AccuracyRange` per range and class."""
        out = []
        for cls, d in self.digits.items():
            low = d < threshold
            if not low.any():
                continue
            for a, b in true_runs(low):
                # split where the arc changes (an excluded gap in between)
                cuts = [a] + [i for i in range(a + 1, b) if self.segment[i] != self.segment[i - 1]]
                for i0, i1 in zip(cuts, cuts[1:] + [b]):
                    k = i0 + int(np.argmin(d[i0:i1]))
                    out.append(AccuracyRange(cls, float(self.q[i0]), float(self.q[i1 - 1]),
                                             float(d[k]), str(self.worst[cls][k]),
                                             float(self.q[k])))
        return out


def amplification(linkage: Linkage, motion: LinkageMotion):
    """How much each solved thing amplifies the rounding of the inputs.

    Returns ``{("link", n) | ("point", name) | ("slide", name) | ("joint", name)
    | ("all",): kappa}``: kappa is the product of 1/sin(gamma) of the dyads the
    thing depends on (through the solving order), an array over the positions
    (1 far from every singular position).  ``("all",)`` is the worst of them.
    """
    frame = linkage.frame
    own = {}
    for c in motion.conditions:
        own[c.element] = 1.0 / np.maximum(np.asarray(c.sin_gamma, dtype=float), EPS)
    point: dict = {}
    link: dict = {}
    out: dict = {}
    worst = np.ones(np.shape(motion.feasible))
    for idx in linkage.order:
        el = linkage.elements[idx]
        pts, lks = el.needs()
        amp = 1.0
        for p in pts:
            amp = np.maximum(amp, point.get(p, 1.0))
        for k in lks:
            if k != frame:
                amp = np.maximum(amp, link.get(k, 1.0))
        if idx in own:
            amp = amp * own[idx]
        made_p, made_l = el.makes()
        for p in made_p:
            point[p] = amp
        for k in made_l:
            link[k] = amp
        for name in el.slide_names(frame):
            out[("slide", name)] = amp
        joint = el.transmission_joint()
        if joint is not None:
            out[("joint", joint)] = amp
        worst = np.maximum(worst, amp)
    out.update({("point", p): a for p, a in point.items()})
    out.update({("link", k): a for k, a in link.items()})
    out[("all",)] = worst
    return out


def _digits(err_over_scale: FloatOrArray):
    """Correct significant digits of a relative error (0 ... FULL_DIGITS)."""
    r = np.maximum(np.asarray(err_over_scale, dtype=float), EPS)
    return np.clip(-np.log10(r), 0.0, FULL_DIGITS)


def natural_scales(linkage: Linkage, sweep: Sweep, q: np.ndarray):
    """``((1, ω, ω² + |α|), L)``: the natural magnitudes of positions, velocities and
    accelerations of the linkage at inputs ``q`` (arrays, per radian: ω and α the
    input's speed and acceleration, divided by the linkage's size ``L`` for a slide);
    a length, velocity or acceleration is ``L`` times its order's.  The round-off of a
    result is measured against them: a quantity that is zero in truth computes as
    noise of about EPS times its natural magnitude."""
    rotary = linkage.driver(sweep.driver).rotary
    L = float(np.max(linkage.scale()))
    speed = np.abs(np.broadcast_to(np.asarray(sweep.speed(q), dtype=float), q.shape))
    accel = np.abs(np.broadcast_to(np.asarray(sweep._at(sweep.ddq, q), dtype=float), q.shape))
    if not rotary:
        speed, accel = speed / L, accel / L
    return (np.ones_like(q), speed, speed * speed + accel), L


def noise_floor(linkage: Linkage, sweep: Sweep, q: np.ndarray, kind: str,
                rel: float = NOISE_REL):
    """The magnitude below which a quantity of ``kind`` (``angle``, ``angvel`` …) at
    inputs ``q`` is round-off, not motion: ``rel`` times the largest natural magnitude
    of its order (:func:`natural_scales`), SI units (:data:`NOISE_REL`).  None for a
    kind without an order."""
    k = _ORDER_OF_KIND.get(kind)
    if k is None or not np.size(q):
        return None
    natural, L = natural_scales(linkage, sweep, np.asarray(q, dtype=float))
    return _floor(natural, k, L, kind, rel)


def _floor(natural: Any, k: int, L: float, kind: str, rel: float = NOISE_REL) -> float:
    """``rel`` times the largest natural magnitude of order ``k``, times ``L`` for a
    length, velocity or acceleration."""
    length = kind in ("length", "velocity", "acceleration")
    return rel * float(np.max(natural[k], initial=0.0)) * (L if length else 1.0)


def estimate_accuracy(linkage: Linkage, sweep: Sweep, quantities: Sequence[Any],
                      values: Dict[str, np.ndarray], extremes: Any, q: np.ndarray,
                      motion: LinkageMotion, segment: Any):
    """Digits-lost estimate of every quantity at inputs ``q`` (see :class:`Accuracy`).

    ``values``/``extremes`` give each quantity's largest magnitude over the
    sweep; ``motion`` is the engine's solution at ``q``; ``segment`` the run
    of every input.
    """
    amp = amplification(linkage, motion)
    natural, L = natural_scales(linkage, sweep, q)
    digits, worst, by_q = {}, {}, {}
    for qt in quantities:
        k = _ORDER_OF_KIND.get(qt.kind)
        if k is None or k > motion.order:
            continue
        v = np.abs(np.asarray(values[qt.symbol], dtype=float))
        peak = float(np.max(v)) if v.size else 0.0
        if qt.symbol in extremes:
            peak = max([peak] + [abs(e.value) for e in extremes[qt.symbol] if e.bounded])
        length = qt.kind in ("length", "velocity", "acceleration")
        if k == 0:
            # an angle is good to EPS of a radian, a length to EPS of the linkage
            peak = max(peak, L if length else 1.0)
        if peak <= _floor(natural, k, L, qt.kind):
            # identically zero (no input speed), or zero in truth and computed as
            # round-off (a coupler's α when it only translates): no digits to count
            # against a peak that is itself noise
            continue
        kappa = amp.get(qt.source, amp[("all",)]) if qt.source else amp[("all",)]
        kappa = np.broadcast_to(kappa, q.shape)
        if k == 0:
            # a position near an assembly limit loses at most half its digits (a square root)
            kappa = np.minimum(kappa, 1.0 / np.sqrt(EPS))
        err = ACCURACY_C[k] * EPS * kappa ** (k + 1) * natural[k] * (L if length else 1.0)
        d = _digits(err / peak)
        by_q[qt.symbol] = float(np.min(d))
        cls = ACCURACY_CLASSES[k]
        if cls not in digits:
            digits[cls] = d.copy()
            worst[cls] = np.full(q.shape, qt.symbol, dtype=object)
        else:
            lower = d < digits[cls]
            digits[cls] = np.where(lower, d, digits[cls])
            worst[cls] = np.where(lower, qt.symbol, worst[cls])
    return Accuracy(q, segment, digits, worst, by_q)


def _accuracy_of_sweep(linkage, sweep, quantities, order,
                       q, values, extremes,
                       motion, runs, toggles):
    """:func:`estimate_accuracy` on the output rows and the refined near-dead positions
    (a singular position between two rows is not missed)."""
    segment = np.repeat(np.arange(len(runs)), [b - a for a, b in runs]) if runs else \
        np.zeros(q.size, dtype=int)
    extra = np.array([t.at for t in toggles
                      if q.size and q[0] <= t.at <= q[-1] and not np.any(q == t.at)],
                     dtype=float)
    if extra.size:
        m_extra = solve(linkage, sweep.inputs(extra), order=order)
        keep = m_extra.regular
        extra = extra[keep]
    if extra.size:
        m_extra = _take(m_extra, np.flatnonzero(keep))
        q_all = np.concatenate([q, extra])
        sort = np.argsort(q_all, kind="stable")
        seg_extra = segment[np.clip(np.searchsorted(q, extra) - 1, 0, max(q.size - 1, 0))]
        seg = np.concatenate([segment, seg_extra])[sort]
        motion = _concat_motion(motion, m_extra, sort)
        q_all = q_all[sort]
    else:
        q_all, seg = q, segment
    return estimate_accuracy(linkage, sweep, quantities, values, extremes, q_all, motion, seg)


def _concat_motion(a: Any, b: Any, sort: bool):
    """Two motions' positions joined, then reordered by ``sort`` (conditions only:
    what the accuracy estimate reads)."""
    def cat(x: FloatOrArray, y: FloatOrArray):
        return None if x is None or y is None else np.concatenate([x, y])[sort]
    cds = tuple(dataclasses.replace(c, sin_gamma=cat(c.sin_gamma, d.sin_gamma),
                                    cos_joint=cat(c.cos_joint, d.cos_joint))
                for c, d in zip(a.conditions, b.conditions))
    return LinkageMotion(a.order, cat(a.feasible, b.feasible), cat(a.regular, b.regular),
                         {}, {}, {}, cds)
