"""The structural analysis (杆组分解) as results and a report block: shared by
``grashof``'s mobility kind and every linkage given by its joints (``kin``, ``force``)."""

from __future__ import annotations

from mechcli.report.table import Block
from mechcli.report.words import say


def structure_results(st):
    """``mechanism_class`` and ``groups`` (``{type, class, links, joints}`` in solving
    order, the drivers first) of a :class:`~mechcli.core.grashof.structure.Structure`."""
    return {"mechanism_class": st.mechanism_class,
            "groups": [{"type": g.type, "class": g.klass, "links": list(g.links),
                        "joints": list(g.joints)} for g in st.groups]}


#: a group's class as the books write it
_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI"}


def structure_block(lang, st, frame):
    """The structural analysis as the book gives it: the driver with the frame, then
    each Assur group in solving order with its class, and the mechanism's class."""
    rows = []
    for g in st.groups:
        if g.type == "driver":
            what = say(lang, "structure.driver", link=g.links[0], frame=frame)
        elif g.klass == 2:
            what = say(lang, "structure.dyad", type=g.type)
        else:
            kind = say(lang, "structure.triad" if g.type == "triad" else "structure.group")
            what = say(lang, "structure.higher_group", kind=kind,
                       klass=_ROMAN.get(g.klass, g.klass))
        rows.append([what, ", ".join(map(str, g.links)), ", ".join(g.joints),
                     _ROMAN.get(g.klass, str(g.klass))])
    title = say(lang, "structure.title", klass=_ROMAN.get(st.mechanism_class))
    return Block(title, headers=[say(lang, "structure.group"), say(lang, "structure.links"),
                                 say(lang, "structure.pairs"), say(lang, "structure.class")],
                 rows=rows)
