"""Spec errors: one line naming the file, the key, what was expected, what was found."""

from __future__ import annotations

from typing import Collection, Optional


class SpecError(ValueError):
    """A problem file (or a ``--set`` override) is invalid; exit code 2.

    Parameters
    ----------
    file : str
        The spec file as the user named it.
    key : str
        Dotted key path, e.g. ``mechanism.l1``; ``""`` for the whole file.
    expected : str
        What a valid value looks like.
    got : str
        What was found.
    suggestion : str, optional
        A did-you-mean hint.
    """

    def __init__(self, file: object, key: str, expected: str, got: str,
                 suggestion: Optional[str] = None) -> None:
        self.file = str(file)
        self.key = key
        self.expected = expected
        self.got = got
        self.suggestion = suggestion
        super().__init__(self.format())

    def format(self) -> str:
        where = self.file
        if self.key:
            table, _, leaf = self.key.rpartition(".")
            if leaf.isdigit() and table:  # an element of an array of tables
                where += f": [{self.key}]"
            else:
                where += f": [{table}] {leaf}" if table else f": {leaf}"
        msg = f"{where}: expected {self.expected}, got {self.got}"
        if self.suggestion:
            msg += f" (did you mean '{self.suggestion}'?)"
        # one line, whatever the spec holds: control and line-separator characters escaped
        return "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii")
                       for c in msg)


#: common slips: a key written as a student would say it -> the keys meant, in order
#: (the first of them the table knows is suggested)
SLIPS = {
    "rpm": ("n1", "n1_rpm", "n0_rpm", "n_mean_rpm"),
    "n": ("n1", "n1_rpm", "n_mean_rpm"),
    "speed": ("omega1", "n1", "omega", "n1_rpm", "omega_mean"),
    "omega": ("omega1",),
    "w": ("omega1", "omega"),
    "w1": ("omega1",),
    "angular_velocity": ("omega1", "omega"),
    "angular_acceleration": ("alpha1",),
    "velocity": ("v1", "omega1"),
    "unit": ("units",),
    "length_unit": ("units",),
}


def slip(name: object, candidates: Collection[str]) -> Optional[str]:
    """The key meant by a common slip (``rpm`` for ``n1``, :data:`SLIPS`), if the table
    has it among *candidates*; else None."""
    for meant in SLIPS.get(str(name).lower().replace("-", "_"), ()):
        if meant in candidates:
            return meant
    return None


def closest(name: object, candidates: Collection[str]) -> Optional[str]:
    """Nearest valid key to *name* (or the key a common slip means: :func:`slip`), or
    None."""
    import difflib  # only when a key is wrong: not on every start-up

    meant = slip(name, candidates)
    if meant is not None:
        return meant
    hits = difflib.get_close_matches(str(name), list(candidates), n=1, cutoff=0.5)
    return hits[0] if hits else None
