"""``@record`` behaves as ``@dataclasses.dataclass(frozen=True, eq=...)`` (mechcli.core.records).

Each case builds the same class body twice, once with the standard decorator and once with
``record``, and compares what a user sees: constructor arguments and their errors, repr,
equality, hashing, immutability, ``dataclasses.fields/replace/asdict``, ``__post_init__``,
subclassing and ``inspect.signature``.
"""

import dataclasses
import inspect
from typing import ClassVar

import pytest

from mechcli.core.records import record


def _pair(eq=True, frozen=True):
    """(standard, record) versions of one class with every kind of field."""
    def body(decorate):
        @decorate
        class Sample:
            """A sample."""
            a: int
            b: float = 2.5
            c: list = dataclasses.field(default_factory=list)
            d: str = dataclasses.field(default="x", repr=False, compare=False)
            e: int = dataclasses.field(default=7, init=False)
            kind: ClassVar[str] = "sample"
        return Sample
    std = body(dataclasses.dataclass(frozen=frozen, eq=eq))
    rec = body(record(eq=eq, frozen=frozen))
    return std, rec


def _outcome(fn):
    try:
        return "ok", fn()
    except Exception as exc:  # noqa: BLE001 -- the exception is the outcome compared
        return type(exc).__name__, None


CALLS = [((1,), {}), ((1, 3.0), {}), ((1, 3.0, [4]), {}), ((1, 3.0, [4], "y"), {}),
         ((), {"a": 1, "d": "z"}), ((1,), {"c": [1, 2]}),
         ((), {}), ((1, 2, 3, 4, 5), {}), ((1,), {"a": 2}), ((1,), {"zz": 2}), ((1,), {"e": 2})]


@pytest.mark.parametrize("eq", [True, False])
@pytest.mark.parametrize("frozen", [True, False])
@pytest.mark.parametrize("args,kwargs", CALLS)
def test_construction_repr_eq_hash_match_the_standard_dataclass(args, kwargs, eq, frozen):
    std, rec = _pair(eq, frozen)
    s, r = _outcome(lambda: std(*args, **kwargs)), _outcome(lambda: rec(*args, **kwargs))
    assert s[0] == r[0]
    if s[0] != "ok":
        return
    s, r = s[1], r[1]
    assert repr(r).replace(rec.__qualname__, "X") == repr(s).replace(std.__qualname__, "X")
    assert dataclasses.asdict(r) == dataclasses.asdict(s)
    assert vars(r) == vars(s)
    twin = rec(*args, **kwargs)
    assert (twin == r) is (eq or twin is r)
    assert (r == dataclasses.replace(r, d="other")) is eq       # d takes no part in ==
    assert (r == s) is False                                     # another class
    assert _outcome(lambda: hash(r))[0] == _outcome(lambda: hash(s))[0]
    if frozen and eq:
        r2 = rec(1, 3.0, (4,))                                   # hashable fields
        s2 = std(1, 3.0, (4,))
        assert hash(r2) == hash(s2)


@pytest.mark.parametrize("eq", [True, False])
def test_frozen_fields_cannot_be_assigned_or_deleted(eq):
    std, rec = _pair(eq)
    for obj in (std(1), rec(1)):
        with pytest.raises(dataclasses.FrozenInstanceError, match="'a'"):
            obj.a = 2
        with pytest.raises(dataclasses.FrozenInstanceError):
            obj.new = 2                               # the decorated class itself: nothing
        with pytest.raises(dataclasses.FrozenInstanceError, match="'b'"):
            del obj.b
    assert rec(1).a == 1


def test_replace_fields_and_is_dataclass_work():
    _, rec = _pair()
    r = rec(1, c=[3])
    assert dataclasses.is_dataclass(rec) and dataclasses.is_dataclass(r)
    assert [f.name for f in dataclasses.fields(r)] == ["a", "b", "c", "d", "e"]
    r2 = dataclasses.replace(r, b=9.0)
    assert (r2.a, r2.b, r2.c, r2.e) == (1, 9.0, [3], 7)
    assert rec.kind == "sample" and "kind" not in vars(r)
    with pytest.raises(ValueError):
        dataclasses.replace(r, e=1)                 # init=False, as for a dataclass


def test_post_init_and_subclasses():
    calls = []

    @record
    class Base:
        x: float

        def __post_init__(self):
            calls.append(type(self).__name__)
            object.__setattr__(self, "twice", 2 * self.x)

    @record
    class Child(Base):
        y: float = 1.0

    c = Child(3.0, y=4.0)
    assert (c.x, c.y, c.twice, calls) == (3.0, 4.0, 6.0, ["Child"])
    assert repr(c) == f"{Child.__qualname__}(x=3.0, y=4.0)"
    assert c != Base(3.0) and Child(3.0, 4.0) == c
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.y = 1.0


def test_signature_and_docstring():
    _, rec = _pair()
    sig = inspect.signature(rec)
    assert list(sig.parameters) == ["a", "b", "c", "d"]
    assert sig.parameters["b"].default == 2.5
    assert repr(sig.parameters["c"].default) == "<factory>"
    assert sig.parameters["a"].default is inspect.Parameter.empty

    @record
    class Bare:
        p: int
        q: ClassVar[int] = 0
    assert Bare.__doc__ == "Bare(p)"


def test_mutable_record_assigns_and_has_no_hash():
    _, rec = _pair(frozen=False)
    r = rec(1)
    r.a = 5
    assert r.a == 5 and rec.__hash__ is None


def test_refused_field_kinds():
    with pytest.raises(TypeError, match="InitVar"):
        @record
        class WithInitVar:
            a: dataclasses.InitVar[int]
