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
    with pytest.raises((ValueError, TypeError)):    # init=False (TypeError from 3.13)
        dataclasses.replace(r, e=1)


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


def _both(body):
    """(standard outcome, record outcome) of decorating *body*'s class both ways."""
    return (_outcome(lambda: body(dataclasses.dataclass(frozen=True))),
            _outcome(lambda: body(record)))


def test_own_eq_and_hash_are_kept_or_decided_as_dataclasses_decide():
    def own_hash(decorate):
        @decorate
        class H:
            a: int

            def __hash__(self):
                return 42
        return hash(H(1))

    def own_eq(decorate):
        @decorate
        class E:
            a: int

            def __eq__(self, other):
                return True
        return hash(E(1)) == hash(E(1)), E(1) == E(2)

    for body in (own_hash, own_eq):
        std, rec = _both(body)
        assert std == rec == ("ok", std[1]), body.__name__


@pytest.mark.parametrize("case", ["order", "own_setattr", "frozen_on_mutable",
                                  "mutable_on_frozen"])
def test_class_creation_errors_are_those_of_dataclasses(case):
    def body(decorate):
        if case == "order":
            @decorate
            class A:
                a: int = 1
                b: int
        elif case == "own_setattr":
            @decorate
            class A:
                a: int

                def __setattr__(self, name, value):
                    pass
        else:
            base_frozen = case == "mutable_on_frozen"
            base = (record(frozen=base_frozen) if decorate is record
                    else dataclasses.dataclass(frozen=base_frozen))

            @base
            class B:
                a: int
            (record(frozen=not base_frozen) if decorate is record
             else dataclasses.dataclass(frozen=not base_frozen))(type("C", (B,), {}))
    std, rec = _both(body)
    assert std[0] == rec[0] == "TypeError"


def test_init_counts_what_the_caller_gave_and_keeps_field_order():
    @record
    class B:
        a: int
        tags: list = dataclasses.field(default_factory=list)

    class C(B):                       # an __init__ that sets something first
        def __init__(self, *args):
            object.__setattr__(self, "extra", 1)
            super().__init__(*args)

    with pytest.raises(TypeError, match="missing 1 required argument: 'a'"):
        C()
    c = C(1)
    assert (c.a, c.tags, c.extra) == (1, [], 1)
    b = B(tags=[2], a=1)
    assert list(vars(b)) == ["a", "tags"]           # field order, as dataclasses
    B.__init__(b, a=3)                              # re-initialised with keywords
    assert (b.a, b.tags) == (3, [])


def test_descriptor_fields_are_refused_and_subclass_signatures_are_their_own():
    class Positive:
        def __set_name__(self, owner, name):
            self.name = "_" + name

        def __get__(self, obj, owner=None):
            return self if obj is None else getattr(obj, self.name)

        def __set__(self, obj, value):
            object.__setattr__(obj, self.name, value)

    with pytest.raises(TypeError, match="descriptor"):
        @record
        class L:
            length: float = Positive()

    @record
    class P:
        a: int
        b: int = 2

    class Q(P):
        def __init__(self, z):
            super().__init__(z, z)

    assert list(inspect.signature(P).parameters) == ["a", "b"]
    assert list(inspect.signature(Q).parameters) == ["z"]
    assert inspect.signature(P) is inspect.signature(P)     # built once
