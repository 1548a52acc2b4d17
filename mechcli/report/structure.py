"""The structural analysis (杆组分解) as results and a report block: shared by
``grashof``'s mobility kind and every linkage given by its joints (``kin``, ``force``)."""

from __future__ import annotations

from mechcli.report.table import Block


def _label(lang, en, zh):
    return zh if lang == "zh" else en


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
            what = _label(lang, f"driver {g.links[0]} with the frame {frame}",
                          f"原动件 {g.links[0]} 与机架 {frame}")
        elif g.klass == 2:
            what = _label(lang, f"dyad {g.type}", f"{g.type} 型 II 级杆组")
        else:
            kind = {"triad": _label(lang, "triad", "三级杆组")}.get(
                g.type, _label(lang, "group", "杆组"))
            what = _label(lang, f"{kind} (class {_ROMAN.get(g.klass, g.klass)})",
                          f"{_ROMAN.get(g.klass, g.klass)} 级{kind}")
        rows.append([what, ", ".join(map(str, g.links)), ", ".join(g.joints),
                     _ROMAN.get(g.klass, str(g.klass))])
    title = _label(lang, f"Structural analysis: a class {_ROMAN.get(st.mechanism_class)} "
                         f"mechanism (groups in solving order)",
                   f"杆组分解: {_ROMAN.get(st.mechanism_class)} 级机构 (按求解顺序)")
    return Block(title, headers=[_label(lang, "group", "杆组"), _label(lang, "links", "构件"),
                                 _label(lang, "pairs", "运动副"), _label(lang, "class", "级别")],
                 rows=rows)
