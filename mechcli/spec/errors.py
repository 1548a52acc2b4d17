"""Spec errors: one line naming the file, the key, what was expected, what was found."""


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

    def __init__(self, file, key, expected, got, suggestion=None):
        self.file = str(file)
        self.key = key
        self.expected = expected
        self.got = got
        self.suggestion = suggestion
        super().__init__(self.format())

    def format(self):
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


def closest(name, candidates):
    """Nearest valid key to *name*, or None."""
    import difflib   # only when a key is wrong: not on every start-up

    hits = difflib.get_close_matches(str(name), list(candidates), n=1, cutoff=0.5)
    return hits[0] if hits else None
