"""``@record``: the frozen dataclasses of mechcli, made without generating code.

Every problem, element and result type of mechcli is a frozen dataclass.  The standard
decorator writes the source of ``__init__``, ``__repr__``, ``__eq__``, ``__hash__``,
``__setattr__`` and ``__delattr__`` for each class and compiles it with ``exec`` (on
Python < 3.13 one ``exec`` per method): about 0.5 ms a class, 17 ms of the 60 ms that
``mechcli kin`` spent beyond ``import numpy`` for the 33 classes on its path.
:func:`record` lets ``dataclasses`` collect the fields (no code generated) and gives the
class the same methods as closures over the field names, so a class costs ~0.03 ms.

What stays the same as ``@dataclasses.dataclass(frozen=True, eq=...)``:

* ``dataclasses.fields``, ``replace``, ``asdict``, ``astuple`` and ``is_dataclass``;
* the constructor's positional and keyword arguments, defaults, ``default_factory``,
  ``field(init=False)`` and ``__post_init__``, and its ``TypeError`` for a missing,
  unexpected or repeated argument;
* ``repr`` (``Name(a=1, b=2)``, fields with ``repr=False`` left out), ``==`` (same class
  and equal field tuples), ``hash`` of a frozen class with ``eq`` (the tuple of the fields
  that take part), and ``FrozenInstanceError`` on assigning or deleting a field.

* the class-creation errors: a field without a default after one with a default, a frozen
  class with its own ``__setattr__``/``__delattr__``, a frozen class on a non-frozen base
  and the reverse; a method the class defines itself (``__eq__``, ``__hash__``, ``__repr__``)
  is kept, with ``__hash__`` decided as ``dataclasses`` decides it.

What differs: ``inspect.signature`` of the class reads ``__signature__`` (built on first
use; ``help()`` shows ``__init__(self, *args, **kwargs)``), and ``__dataclass_params__``
records what ``dataclasses`` itself generated (nothing), so a class made with
``@dataclasses.dataclass(frozen=True)`` cannot subclass a record; subclass a record with
``@record``.  ``InitVar``, ``kw_only`` and descriptor-typed fields are refused.  A record
is constructed 1.0-1.8x as slowly as a dataclass (~0.4 µs more with defaults filled in):
mechcli builds records per solve, never per position.
"""

from __future__ import annotations

import dataclasses
import reprlib
from typing import TYPE_CHECKING, Any, Callable, FrozenSet, List, Optional, Tuple, TypeVar, overload

__all__ = ["record"]

if TYPE_CHECKING:   # checkers and editors see a record's fields and constructor
    import inspect

    from typing_extensions import dataclass_transform
else:
    def dataclass_transform(**_kwargs: Any) -> Callable[[_T], _T]:
        """``typing.dataclass_transform`` (PEP 681) only matters to type checkers: at run
        time a no-op (no ``typing_extensions`` dependency, Python 3.9 included)."""
        return lambda f: f

_MISSING = dataclasses.MISSING
#: dataclasses' own private marker of an InitVar field (not in its type stubs)
_INITVAR = dataclasses._FIELD_INITVAR  # type: ignore[attr-defined]
_T = TypeVar("_T")


@overload
def record(cls: type[_T], *, eq: bool = True, frozen: bool = True) -> type[_T]: ...


@overload
def record(cls: None = None, *, eq: bool = True,
           frozen: bool = True) -> Callable[[type[_T]], type[_T]]: ...


@dataclass_transform(field_specifiers=(dataclasses.field,))
def record(cls: Optional[type] = None, *, eq: bool = True, frozen: bool = True) -> Any:
    """The class *cls* as ``@dataclasses.dataclass(frozen=frozen, eq=eq)`` would make it
    (see the module's docstring); ``@record`` or ``@record(eq=False)``."""
    if cls is None:
        return lambda c: _make(c, eq, frozen)
    return _make(cls, eq, frozen)


def _is_frozen(base: Any) -> bool:
    """Whether a dataclass *base* is frozen (a record says so itself)."""
    own = base.__dict__.get("_record_frozen")
    return own if own is not None else base.__dataclass_params__.frozen


def _make(cls: Any, eq: bool, frozen: bool) -> Any:
    name = cls.__qualname__
    own = cls.__dict__
    if not own.get("__doc__"):
        names = [n for n, t in own.get("__annotations__", {}).items()
                 if "ClassVar" not in str(t)]
        cls.__doc__ = f"{cls.__name__}({', '.join(names)})"
    bases = [b for b in cls.__mro__[1:] if "__dataclass_fields__" in b.__dict__]
    if bases:
        if any(_is_frozen(b) for b in bases) and not frozen:
            raise TypeError("cannot inherit non-frozen dataclass from a frozen one")
        if not any(_is_frozen(b) for b in bases) and frozen:
            raise TypeError("cannot inherit frozen dataclass from a non-frozen one")
    if frozen:
        for method in ("__setattr__", "__delattr__"):
            if method in own:
                raise TypeError(f"Cannot overwrite attribute {method} in class {name}")
    # has the class its own __hash__ (not the None Python sets beside an own __eq__)?
    explicit_hash = "__hash__" in own and not (own["__hash__"] is None and "__eq__" in own)
    cls = dataclasses.dataclass(cls, init=False, repr=False, eq=False, frozen=False)
    cls._record_frozen = frozen
    fields = dataclasses.fields(cls)
    for f in cls.__dataclass_fields__.values():
        if f._field_type is _INITVAR or getattr(f, "kw_only", False) is True:
            raise TypeError(f"{name}.{f.name}: @record has no InitVar or kw_only fields")
        if hasattr(type(f.default), "__set__"):
            raise TypeError(f"{name}.{f.name}: @record has no descriptor-typed fields")
    init_fields = [f for f in fields if f.init]
    seen_default = None
    for f in init_fields:
        if f.default is not _MISSING or f.default_factory is not _MISSING:
            seen_default = f.name
        elif seen_default:
            raise TypeError(f"non-default argument {f.name!r} follows default argument")
    if "__init__" not in own:
        cls.__init__ = _init(cls, init_fields, [f for f in fields if not f.init], frozen)
        cls.__signature__ = _LazySignature(cls.__init__, init_fields)
    if "__repr__" not in own:
        cls.__repr__ = _repr(tuple(f.name for f in fields if f.repr))
    if eq and "__eq__" not in own:
        cls.__eq__ = _eq(tuple(f.name for f in fields if f.compare))
    if eq and not explicit_hash:   # dataclasses' rule (unsafe_hash=False)
        if frozen:
            cls.__hash__ = _hash(tuple(f.name for f in fields
                                       if (f.compare if f.hash is None else f.hash)))
        else:
            cls.__hash__ = None
    if frozen:
        cls.__setattr__, cls.__delattr__ = _frozen(cls, frozenset(f.name for f in fields))
    return cls


def _init(cls: Any, init_fields: List[dataclasses.Field], other_fields: List[dataclasses.Field],
          frozen: bool) -> Callable[..., None]:
    names = tuple(f.name for f in init_fields)
    known = frozenset(names)
    count = len(names)
    defaults = tuple((f.default, f.default_factory) for f in init_fields)
    # a field outside __init__ with a plain default is read from the class, as in dataclasses
    later = tuple((f.name, f.default_factory) for f in other_fields
                  if f.default_factory is not _MISSING)
    post_init = hasattr(cls, "__post_init__")
    qualname = cls.__qualname__

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) > count:
            raise TypeError(f"{qualname}.__init__() takes {count + 1} positional "
                            f"arguments but {len(args) + 1} were given")
        if kwargs or len(args) < count:
            given = dict(zip(names, args))
            for name, value in kwargs.items():
                if name not in known:
                    raise TypeError(f"{qualname}.__init__() got an unexpected keyword "
                                    f"argument {name!r}")
                if name in given:
                    raise TypeError(f"{qualname}.__init__() got multiple values for "
                                    f"argument {name!r}")
                given[name] = value
            values, missing = [], []
            for name, (default, factory) in zip(names, defaults):
                if name in given:
                    values.append(given[name])
                elif default is not _MISSING:
                    values.append(default)
                elif factory is not _MISSING:
                    values.append(factory())
                else:
                    missing.append(name)
            if missing:
                raise TypeError(f"{qualname}.__init__() missing {len(missing)} required "
                                f"argument{'s' if len(missing) > 1 else ''}: "
                                + ", ".join(repr(n) for n in missing))
        else:   # (a tuple, only read below)
            values = args   # type: ignore[assignment]
        if frozen:   # (no descriptor fields: refused above) straight into the instance
            self.__dict__.update(zip(names, values))
            for name, factory in later:
                self.__dict__[name] = factory()
        else:        # a mutable record honours a __setattr__ or property of its own
            for name, value in zip(names, values):
                setattr(self, name, value)
            for name, factory in later:
                setattr(self, name, factory())
        if post_init:
            self.__post_init__()

    __init__.__qualname__ = f"{qualname}.__init__"
    return __init__


class _Factory:
    def __repr__(self) -> str:
        return "<factory>"


_FACTORY = _Factory()


class _LazySignature:
    """``cls.__signature__``: the constructor's signature, built on first use; None (let
    :func:`inspect.signature` look at ``__init__``) for a subclass with its own
    ``__init__``."""

    def __init__(self, init: Callable[..., None], fields: List[dataclasses.Field]) -> None:
        self.init, self.fields = init, fields
        self.signature: Optional[inspect.Signature] = None

    def __get__(self, obj: object, owner: Optional[type] = None) -> Optional[inspect.Signature]:
        # the class's own __init__ (not a bound one) is compared: mypy's caution is moot
        if (owner if owner is not None else type(obj)).__init__ is not self.init:  # type: ignore[misc]
            return None
        if self.signature is None:
            import inspect

            P = inspect.Parameter
            self.signature = inspect.Signature([
                P(f.name, P.POSITIONAL_OR_KEYWORD, annotation=f.type,
                  default=(f.default if f.default is not _MISSING
                           else P.empty if f.default_factory is _MISSING else _FACTORY))
                for f in self.fields], return_annotation=None)
        return self.signature


def _repr(names: Tuple[str, ...]) -> Callable[[Any], str]:
    @reprlib.recursive_repr()
    def __repr__(self) -> str:
        return (f"{type(self).__qualname__}("
                + ", ".join(f"{n}={getattr(self, n)!r}" for n in names) + ")")
    return __repr__


def _eq(names: Tuple[str, ...]) -> Callable[[Any, object], Any]:
    def __eq__(self, other: object) -> Any:
        if other.__class__ is self.__class__:
            return tuple(getattr(self, n) for n in names) \
                == tuple(getattr(other, n) for n in names)
        return NotImplemented
    return __eq__


def _hash(names: Tuple[str, ...]) -> Callable[[Any], int]:
    def __hash__(self) -> int:
        return hash(tuple(getattr(self, n) for n in names))
    return __hash__


def _frozen(cls: Any, names: FrozenSet[str]) -> Tuple[Callable[..., None], Callable[..., None]]:
    def __setattr__(self, name: str, value: Any) -> None:
        if type(self) is cls or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)

    def __delattr__(self, name: str) -> None:
        if type(self) is cls or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)
    return __setattr__, __delattr__
