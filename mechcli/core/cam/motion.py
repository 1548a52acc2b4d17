"""Follower motion laws and motion programs (rise, dwell, return segments).

A *motion law* is a normalized function ``f(u)`` on ``u in [0, 1]`` with
``f(0) = 0`` and ``f(1) = 1``, given together with its exact derivatives
``f'``, ``f''``, ``f'''`` as closed-form *pieces* (a law is smooth inside each
piece; a piece boundary may carry a jump of ``f''`` such as the midpoint of the
parabolic law).  A *motion program* strings rise / dwell / return segments
around the 360 degrees of the cam and gives the follower displacement ``s``
(m, or rad for an oscillating follower) and its derivatives with respect to
the cam angle ``delta`` (rad).

Notes
-----
The book's four laws are those of 表 4-1 (uniform velocity 等速, constant
acceleration/deceleration 等加速等减速, cosine acceleration 余弦加速度 (simple
harmonic), sine acceleration 正弦加速度 (cycloidal)).  The cubic ``3u² − 2u³``
(the lowest polynomial with zero velocity at both ends), the 3-4-5 and 4-5-6-7
polynomials, the modified trapezoid and the modified sine are the standard
laws of modern cam design (their acceleration shapes are integrated here in
closed form).  Any other polynomial ``f(u) = Σ c_k u^k`` is a
:class:`PolynomialLaw`.  A return segment uses ``s = s_start - lift * f(u)``,
which reproduces the return column of 表 4-1.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING, Any, Callable, List, Optional, Tuple, Union

import numpy as np

from mechcli.core.errors import DescribedError
from mechcli.core.records import record

if TYPE_CHECKING:
    from mechcli.core.types import FloatOrArray

#: the law names accepted by :func:`law_pieces`
LAWS = ("uniform", "parabolic", "cosine", "sine", "cubic", "poly345", "poly4567",
        "modified-trapezoid", "modified-sine")

#: alternative names (textbook English and Chinese-pinyin-free synonyms)
LAW_ALIASES = {
    "constant-velocity": "uniform", "linear": "uniform",
    "constant-acceleration": "parabolic",
    "harmonic": "cosine", "simple-harmonic": "cosine",
    "cycloidal": "sine",
    "3-4-5": "poly345", "4-5-6-7": "poly4567",
    "poly23": "cubic", "2-3": "cubic",
}

#: coefficients ``c_0 … c_n`` of ``f(u) = Σ c_k u^k`` of the named polynomial laws
POLYNOMIAL_LAWS = {
    "cubic": (0.0, 0.0, 3.0, -2.0),
    "poly345": (0.0, 0.0, 0.0, 10.0, -15.0, 6.0),
    "poly4567": (0.0, 0.0, 0.0, 0.0, 35.0, -84.0, 70.0, -20.0),
}

SEGMENT_KINDS = ("rise", "dwell", "return")


@record
class LawPiece:
    """One smooth piece of a normalized motion law.

    Attributes
    ----------
    u0, u1 : float
        The piece covers ``u0 <= u <= u1`` of the normalized angle.
    func : callable
        ``func(u) -> (f, f1, f2, f3)``: normalized displacement and its first
        three derivatives with respect to ``u`` (exact, closed form).
    """

    u0: float
    u1: float
    func: Callable[..., Any]


def _uniform(u: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    one = np.ones_like(u)
    return u, one, 0.0 * u, 0.0 * u


def _parabolic_a(u: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    return 2 * u ** 2, 4 * u, 4.0 + 0 * u, 0.0 * u


def _parabolic_b(u: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    w = 1 - u
    return 1 - 2 * w ** 2, 4 * w, -4.0 + 0 * u, 0.0 * u


def _cosine(u: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    p = math.pi
    return ((1 - np.cos(p * u)) / 2, p / 2 * np.sin(p * u), p ** 2 / 2 * np.cos(p * u),
            -p ** 3 / 2 * np.sin(p * u))


def _sine(u: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    t = 2 * math.pi
    return (u - np.sin(t * u) / t, 1 - np.cos(t * u), t * np.sin(t * u),
            t ** 2 * np.cos(t * u))


def _poly(coeffs: List[float]) -> Callable[..., Any]:
    """Polynomial law ``sum c_k u^k`` with its exact derivatives."""
    c = np.polynomial.Polynomial(coeffs)
    d1, d2, d3 = c.deriv(1), c.deriv(2), c.deriv(3)

    def func(u: FloatOrArray) -> Any:
        return c(u), d1(u), d2(u), d3(u)
    return func


@record
class PolynomialLaw:
    """A motion law given by its coefficients: ``f(u) = Σ_k c_k u^k``, ``u = δ/δ0``.

    Dimensionless: the segment's displacement is ``s_start + lift f(u)`` (rise)
    or ``s_start − lift f(u)`` (return), so ``f(0) = 0`` and ``f(1) = 1`` are
    needed for the segment to start where the previous one ended and to cover
    its lift; :func:`build_program` checks both (to 1e-9).  A law with
    ``f'(0) ≠ 0`` or ``f''(0) ≠ 0`` (or at ``u = 1``) is allowed: the velocity
    or acceleration jump against the neighbouring segment is an
    :class:`Impact` like any other law's.

    Attributes
    ----------
    coefficients : tuple of float
        ``c_0, c_1, …, c_n`` (at least two), finite.

    Notes
    -----
    The book's form ``s = C_0 + C_1 δ + … + C_n δ^n`` (δ in rad, s in m) is
    this law with ``c_k = C_k δ0^k / h``.
    """

    coefficients: tuple

    def __post_init__(self) -> None:
        c = tuple(float(x) for x in self.coefficients)
        if len(c) < 2 or not all(math.isfinite(x) for x in c):
            raise ValueError("a polynomial law needs at least two finite coefficients")
        object.__setattr__(self, "coefficients", c)

    def ends(self) -> Tuple[Tuple[float, ...], ...]:
        """``(f, f', f'')`` at ``u = 0`` and at ``u = 1``: two tuples of 3 floats."""
        c = np.polynomial.Polynomial(self.coefficients)
        return tuple(tuple(float(c.deriv(k)(u)) if k else float(c(u)) for k in range(3))
                     for u in (0.0, 1.0))

    def extremes(self) -> Tuple[float, float, float, float]:
        """Smallest and largest ``f`` on ``0 ≤ u ≤ 1``.

        Returns
        -------
        tuple
            ``(f_min, u_at_min, f_max, u_at_max)``: from the ends and the roots
            of ``f'`` inside ``(0, 1)`` (their real parts: a double root comes
            out of the eigenvalue solver as a pair ``x ± 1e-8 i``, and ``f`` at
            a point that is not an extreme changes nothing).
        """
        c = np.polynomial.Polynomial(self.coefficients)
        cand = [0.0, 1.0]
        d = c.deriv().trim()
        if d.degree() > 0:
            cand += [float(x.real) for x in np.atleast_1d(d.roots()) if 0.0 < x.real < 1.0]
        u = np.array(cand)
        f = c(u)
        lo, hi = int(np.argmin(f)), int(np.argmax(f))
        return float(f[lo]), float(u[lo]), float(f[hi]), float(u[hi])

    def __str__(self) -> str:
        """``3u² − 2u³``: the book's way of writing the law (superscript powers)."""
        sup = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
        terms = []
        for k, ck in enumerate(self.coefficients):
            if ck == 0:
                continue
            mag = abs(ck)
            num = "" if (mag == 1 and k) else f"{mag:.10g}"
            var = "" if k == 0 else "u" if k == 1 else "u" + str(k).translate(sup)
            terms.append(("−" if ck < 0 else "+", num + var))
        if not terms:
            return "0"
        first = ("−" if terms[0][0] == "−" else "") + terms[0][1]
        return first + "".join(f" {s} {x}" for s, x in terms[1:])


_named_polys = {name: _poly(list(c)) for name, c in POLYNOMIAL_LAWS.items()}


def _trig_piece(u0: float, c0: float, cs: float, cc: float, k: float, v0: float, s0: float,
                scale: float) -> Callable[..., Any]:
    """Piece with acceleration ``c0 + cs sin(k t) + cc cos(k t)``, ``t = u - u0``.

    Integrated in closed form from start velocity *v0* and displacement *s0*;
    everything is multiplied by *scale* (the normalization ``1/f(1)``).
    """

    def func(u: FloatOrArray) -> Any:
        t = u - u0
        sn, cn = np.sin(k * t), np.cos(k * t)
        acc = c0 + cs * sn + cc * cn
        jerk = cs * k * cn - cc * k * sn
        vel = v0 + c0 * t + cs * (1 - cn) / k + cc * sn / k
        dis = s0 + v0 * t + c0 * t ** 2 / 2 + cs * (t - sn / k) / k + cc * (1 - cn) / k ** 2
        return scale * dis, scale * vel, scale * acc, scale * jerk
    return func


def _acc_shape_pieces(shape: List[Tuple[float, ...]]) -> Any:
    """Integrate a piecewise acceleration shape into normalized law pieces.

    *shape* is a list of ``(u0, u1, c0, cs, cc, k)``: acceleration
    ``c0 + cs sin(k (u-u0)) + cc cos(k (u-u0))`` on ``[u0, u1]`` with unit
    peak; the result is scaled so that ``f(1) = 1``.
    """
    starts = []
    v, s = 0.0, 0.0
    for (u0, u1, c0, cs, cc, k) in shape:
        starts.append((v, s))
        f = _trig_piece(u0, c0, cs, cc, k, v, s, 1.0)
        s, v = (float(x) for x in f(np.float64(u1))[:2])
    scale = 1.0 / s
    return tuple(LawPiece(u0, u1, _trig_piece(u0, c0, cs, cc, k, v0, s0, scale))
                 for (u0, u1, c0, cs, cc, k), (v0, s0) in zip(shape, starts))


@functools.cache
def law_pieces(law: Union[PolynomialLaw, str]) -> Any:
    """The closed-form pieces of a normalized motion law.

    Parameters
    ----------
    law : str or PolynomialLaw
        One of :data:`LAWS` (or an alias of :data:`LAW_ALIASES`), or a
        polynomial given by its coefficients.

    Returns
    -------
    tuple of LawPiece
        Pieces covering ``[0, 1]`` in order.

    Notes
    -----
    Modified trapezoid: acceleration rises as a sine over ``u in [0, 1/8]``,
    stays constant to ``3/8``, falls as a cosine to ``5/8``, stays constant to
    ``7/8`` and returns to zero at ``1`` (peak ``4.888 h/β²``).  Modified sine:
    sine quarter-waves of period ``1/2`` on ``[0, 1/8]`` and ``[7/8, 1]`` joined
    by a cosine of period ``3/2`` (peak ``5.528 h/β²``).
    """
    if isinstance(law, PolynomialLaw):
        return (LawPiece(0.0, 1.0, _poly(list(law.coefficients))),)
    law = LAW_ALIASES.get(law, law)
    w = 4 * math.pi
    if law == "uniform":
        return (LawPiece(0.0, 1.0, _uniform),)
    if law == "parabolic":
        return (LawPiece(0.0, 0.5, _parabolic_a), LawPiece(0.5, 1.0, _parabolic_b))
    if law == "cosine":
        return (LawPiece(0.0, 1.0, _cosine),)
    if law == "sine":
        return (LawPiece(0.0, 1.0, _sine),)
    if law in _named_polys:
        return (LawPiece(0.0, 1.0, _named_polys[law]),)
    if law == "modified-trapezoid":
        return _acc_shape_pieces([
            (0.0, 1 / 8, 0.0, 1.0, 0.0, w),
            (1 / 8, 3 / 8, 1.0, 0.0, 0.0, w),
            (3 / 8, 5 / 8, 0.0, 0.0, 1.0, w),
            (5 / 8, 7 / 8, -1.0, 0.0, 0.0, w),
            (7 / 8, 1.0, 0.0, 0.0, -1.0, w),
        ])
    if law == "modified-sine":
        return _acc_shape_pieces([
            (0.0, 1 / 8, 0.0, 1.0, 0.0, w),
            (1 / 8, 7 / 8, 0.0, 0.0, 1.0, w / 3),
            (7 / 8, 1.0, 0.0, 0.0, -1.0, w),
        ])
    raise ValueError(f"unknown motion law '{law}'; valid: {', '.join(LAWS)}")


def law_values(law: Union[PolynomialLaw, str], u: np.ndarray) -> Tuple[np.ndarray, ...]:
    """Normalized displacement and derivatives of *law* at *u* (array in [0, 1]).

    Returns
    -------
    tuple of 4 ndarray
        ``f, f', f'', f'''`` (derivatives with respect to ``u``).  At a piece
        boundary the right-hand piece is used (the last piece includes ``u = 1``).
    """
    u = np.asarray(u, dtype=float)
    out = [np.zeros_like(u) for _ in range(4)]
    pieces = law_pieces(law)
    for i, p in enumerate(pieces):
        last = i == len(pieces) - 1
        mask = (u >= p.u0) & ((u <= p.u1) if last else (u < p.u1))
        if i == 0:
            mask |= u < p.u0
        if last:
            mask |= u > p.u1
        if np.any(mask):
            vals = p.func(u[mask])
            for o, v in zip(out, vals):
                o[mask] = v
    return tuple(out)


@record
class Segment:
    """One segment of a motion program.

    Attributes
    ----------
    kind : str
        ``rise``, ``dwell`` or ``return``.
    start : float
        Cam angle at the start of the segment, rad.
    span : float
        Cam angle the segment lasts (δ0, δ01, δ'0, δ02 of the book), rad.
    law : str, PolynomialLaw or None
        Motion law (None for a dwell).
    s_start : float
        Follower displacement at the start (m, or rad when oscillating).
    lift : float
        Signed change of displacement over the segment (positive for a rise,
        negative for a return, zero for a dwell).
    """

    kind: str
    start: float
    span: float
    law: str | None
    s_start: float
    lift: float

    @property
    def end(self) -> float:
        return self.start + self.span

    def pieces(self) -> Any:
        """``(delta0, delta1, LawPiece or None)`` smooth pieces of this segment."""
        if self.law is None:
            return [(self.start, self.end, None)]
        return [(self.start + p.u0 * self.span, self.start + p.u1 * self.span, p)
                for p in law_pieces(self.law)]


@record
class MotionState:
    """Follower displacement and its derivatives with respect to the cam angle.

    Attributes
    ----------
    delta : ndarray
        Cam angle, rad.
    s, s1, s2, s3 : ndarray
        Displacement (m or rad) and ``ds/dδ``, ``d²s/dδ²``, ``d³s/dδ³`` (per rad,
        per rad², per rad³).  Multiply by ω, ω², ω³ for velocity, acceleration
        and jerk in time.
    """

    delta: np.ndarray
    s: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray


def _piece_state(seg: Segment, piece: Optional[LawPiece], delta: np.ndarray
                ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    delta = np.asarray(delta, dtype=float)
    if piece is None:
        z = np.zeros_like(delta)
        return z + seg.s_start, z, z.copy(), z.copy()
    u = (delta - seg.start) / seg.span
    f, f1, f2, f3 = piece.func(u)
    b = seg.span
    return (seg.s_start + seg.lift * f, seg.lift * f1 / b, seg.lift * f2 / b ** 2,
            seg.lift * f3 / b ** 3)


@record
class Impact:
    """A jump of follower velocity (rigid impact) or acceleration (soft impact).

    Attributes
    ----------
    delta : float
        Cam angle, rad.
    kind : str
        ``rigid`` (刚性冲击: finite velocity jump, infinite acceleration) or
        ``soft`` (柔性冲击: finite acceleration jump, infinite jerk).
    jump : float
        Size of the jump of ``ds/dδ`` (rigid) or ``d²s/dδ²`` (soft), per rad
        or per rad².
    """

    delta: float
    kind: str
    jump: float


@record
class MotionProgram:
    """Rise / dwell / return segments covering one cam revolution.

    Attributes
    ----------
    segments : tuple of Segment
        In order, starting at δ = 0 and summing to 2π.
    stroke : float
        Largest displacement reached (lift h in m, or swing ψ in rad).
    angular : bool
        True for an oscillating follower (displacements are angles).
    """

    segments: tuple
    stroke: float
    angular: bool = False

    def pieces(self) -> Any:
        """All smooth pieces ``(seg_index, delta0, delta1, LawPiece or None)``."""
        return [(i, d0, d1, p) for i, seg in enumerate(self.segments)
                for d0, d1, p in seg.pieces()]

    def piece_state(self, k: int, delta: np.ndarray
                   ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """State on piece *k* of :meth:`pieces` (its formula, even at its ends)."""
        i, _, _, p = self.pieces()[k]
        return _piece_state(self.segments[i], p, delta)

    def evaluate(self, delta: np.ndarray, left: Optional[np.ndarray] = None) -> MotionState:
        """Displacement and derivatives at cam angles *delta* (rad, any array).

        Angles are taken modulo 2π; at a piece boundary the following piece is
        used (one-sided from the right), except where *left* is true.

        Parameters
        ----------
        delta : array_like
            Cam angles, rad.
        left : array_like of bool, optional
            Where true, the limit from the left: at a piece boundary the piece
            that ends there, evaluated by its own formula at its end (exact, no
            nudge); δ = 0 (mod 2π) is then the end of the last piece.
        """
        delta = np.asarray(delta, dtype=float)
        d = np.mod(delta, 2 * math.pi)
        out = [np.zeros_like(d) for _ in range(4)]
        pieces = self.pieces()
        bounds = np.array([p[1] for p in pieces])
        idx = np.clip(np.searchsorted(bounds, d, side="right") - 1, 0, len(pieces) - 1)
        if left is not None:
            left = np.broadcast_to(np.asarray(left, dtype=bool), d.shape)
            dl = np.where(d > 0.0, d, 2 * math.pi)
            il = np.clip(np.searchsorted(bounds, dl, side="left") - 1, 0, len(pieces) - 1)
            idx = np.where(left, il, idx)
            d = np.where(left, dl, d)
        for k in np.unique(idx):
            mask = idx == k
            vals = self.piece_state(int(k), d[mask])
            for o, v in zip(out, vals):
                o[mask] = v
        return MotionState(delta, *out)

    def impacts(self, rtol: float = 1e-9) -> Any:
        """Velocity and acceleration jumps around the cycle.

        Returns
        -------
        tuple of Impact
            One entry per cam angle where ``ds/dδ`` jumps (rigid) or, if not,
            ``d²s/dδ²`` jumps (soft), in increasing angle.
        """
        pieces = self.pieces()
        out = []
        n = len(pieces)
        scale_v = max(self.stroke / min(s.span for s in self.segments), 1e-300)
        for k in range(n):
            prev = (k - 1) % n
            _, p0, p1, _ = pieces[prev]
            d = pieces[k][1]
            left = self.piece_state(prev, np.array([p1]))
            right = self.piece_state(k, np.array([d]))
            jv = float(right[1][0] - left[1][0])
            ja = float(right[2][0] - left[2][0])
            span = min(self.segments[pieces[k][0]].span, self.segments[pieces[prev][0]].span)
            if abs(jv) > rtol * scale_v:
                out.append(Impact(d, "rigid", jv))
            elif abs(ja) > rtol * scale_v / span:
                out.append(Impact(d, "soft", ja))
        return tuple(out)


    def jumps(self, rtol: float = 1e-9) -> Any:
        """Cam angles where the motion jumps: ds/dδ, d²s/dδ² or d³s/dδ³ differ on the
        two sides of a piece boundary (segment ends, the parabolic law's midpoint).

        Parameters
        ----------
        rtol : float
            A difference counts when larger than *rtol* × stroke / β^k (k = 1, 2,
            3 for the three derivatives; β the shorter of the two segments that
            meet), the scale of :meth:`impacts`.

        Returns
        -------
        tuple of float
            Piece starts in ``[0, 2π)``, rad, increasing (each the exact float of
            :meth:`pieces`).  A jump of the displacement itself cannot happen
            (:func:`build_program` makes the segments meet).
        """
        pieces = self.pieces()
        n = len(pieces)
        out = []
        for k in range(n):
            prev = (k - 1) % n
            left = self.piece_state(prev, np.array([pieces[prev][2]]))
            right = self.piece_state(k, np.array([pieces[k][1]]))
            span = min(self.segments[pieces[k][0]].span, self.segments[pieces[prev][0]].span)
            if any(abs(float(r[0] - l[0])) > rtol * self.stroke / span ** m
                   for m, (l, r) in enumerate(zip(left[1:], right[1:]), start=1)):
                out.append(pieces[k][1])
        return tuple(out)


def jump_samples(program: MotionProgram, delta: np.ndarray, rtol: float = 1e-9
                ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sample angles with both sides of every jump of *program*.

    Parameters
    ----------
    program : MotionProgram
    delta : ndarray
        Increasing cam angles, rad (the uniform grid, 0 … 2π).
    rtol : float
        As :meth:`MotionProgram.jumps`.

    Returns
    -------
    delta, left, grid : ndarray
        At every jump angle (and its images by 2π) after ``delta[0]`` and up to
        ``delta[-1]``, two samples at the same angle: the limit from the left
        (``left`` true), then from the right.  A grid angle within 1e-9 of a step
        of a jump is moved onto it (the jump's exact float); a jump between grid
        angles gets two new samples.  ``grid`` marks the samples of *delta* (their
        right-hand rows).  The first angle keeps one sample (nothing lies to its
        left in the range).
    """
    delta = np.asarray(delta, dtype=float)
    jumps = np.array(program.jumps(rtol))
    n = len(delta)
    if not len(jumps) or n < 2:
        return delta, np.zeros(n, dtype=bool), np.ones(n, dtype=bool)
    period = 2 * math.pi
    lo, hi = delta[0], delta[-1]
    step = (hi - lo) / (n - 1)
    tol = 1e-9 * step
    m = np.arange(math.floor((lo - jumps.max()) / period), math.ceil((hi - jumps.min()) / period)
                  + 1)
    cand = (jumps[None, :] + period * m[:, None]).ravel()
    cand = np.sort(cand[(cand > lo + tol) & (cand <= hi + tol)])
    d = delta.copy()
    near = np.clip(np.searchsorted(d, cand), 1, n - 1)
    near = np.where(np.abs(d[near - 1] - cand) < np.abs(d[near] - cand), near - 1, near)
    on = np.abs(d[near] - cand) <= tol
    d[near[on]] = cand[on]
    rows = np.concatenate([d, cand, cand[~on]])
    left = np.concatenate([np.zeros(n, dtype=bool), np.ones(len(cand), dtype=bool),
                           np.zeros(int(np.count_nonzero(~on)), dtype=bool)])
    grid = np.concatenate([np.ones(n, dtype=bool), np.zeros(len(rows) - n, dtype=bool)])
    order = np.lexsort((~left, rows))
    return rows[order], left[order], grid[order]


def build_program(segments: Any, stroke: float, angular: bool = False) -> MotionProgram:
    """Make a :class:`MotionProgram` from ``(kind, span, law, lift)`` tuples.

    Parameters
    ----------
    segments : sequence of (str, float, str or PolynomialLaw or None, float)
        Kind (``rise``/``dwell``/``return``), span (rad), law (a name, a
        :class:`PolynomialLaw`, None for a dwell) and lift magnitude (m or rad;
        ignored for a dwell).
    stroke : float
        Lift h (m) or swing ψ (rad) of the program.
    angular : bool
        True for an oscillating follower.

    Raises
    ------
    ValueError
        If the spans do not sum to 2π, the follower does not come back to its
        start, the displacement leaves ``[0, stroke]``, or a polynomial law
        does not go from ``f(0) = 0`` to ``f(1) = 1`` (the spans: a
        :class:`~mechcli.core.errors.DescribedError`, reason ``"span_sum"``,
        value ``total`` [rad]).  The spec layer checks all of this first and
        names the key.
    """
    out = []
    start = 0.0
    s = 0.0
    for kind, span, law, lift in segments:
        if kind not in SEGMENT_KINDS:
            raise ValueError(f"unknown segment kind '{kind}'")
        if not span > 0:
            raise ValueError("segment spans must be positive")
        if isinstance(law, PolynomialLaw) and kind != "dwell":
            (f0, *_), (f1, *_) = law.ends()
            if abs(f0) > 1e-9 or abs(f1 - 1.0) > 1e-9:
                raise ValueError(f"the polynomial law {law} does not go from 0 to 1 "
                                 f"(f(0) = {f0:g}, f(1) = {f1:g})")
        signed = 0.0 if kind == "dwell" else (lift if kind == "rise" else -lift)
        out.append(Segment(kind, start, span, None if kind == "dwell" else
                           LAW_ALIASES.get(law, law), s, signed))
        start += span
        s += signed
        if s < -1e-12 * stroke or s > stroke * (1 + 1e-12):
            raise ValueError("the displacement leaves [0, stroke]")
    if abs(start - 2 * math.pi) > 1e-9:
        raise DescribedError("the segment spans do not sum to a full turn", "span_sum",
                             total=start)
    if abs(s) > 1e-9 * stroke:
        raise ValueError("the follower does not return to its start position")
    return MotionProgram(tuple(out), stroke, angular)
