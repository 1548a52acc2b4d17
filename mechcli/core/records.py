"""``@record``: the frozen dataclasses of mechcli, made without generating code.

Every problem, element and result type of mechcli is a frozen dataclass.  The standard
decorator writes the source of ``__init__``, ``__repr__``, ``__eq__``, ``__hash__``,
``__setattr__`` and ``__delattr__`` for each class and compiles it with ``exec`` (on
Python < 3.13 one ``exec`` per method): about 0.5 ms a class, 17 ms of the 60 ms that
``mechcli kin`` spent beyond ``import numpy`` for the 33 classes on its path (issue 17).
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

What differs: ``inspect.signature`` of the class reads ``__signature__`` (built on first
use), and ``__dataclass_params__`` records what ``dataclasses`` itself generated (nothing),
so a class made with ``@dataclasses.dataclass(frozen=True)`` cannot subclass a record;
subclass a record with ``@record``.  ``InitVar`` and ``kw_only`` fields are refused.
"""

from __future__ import annotations

import dataclasses
import reprlib

__all__ = ["record"]

_MISSING = dataclasses.MISSING


def record(cls=None, *, eq=True, frozen=True):
    """The class *cls* as ``@dataclasses.dataclass(frozen=frozen, eq=eq)`` would make it
    (see the module's docstring); ``@record`` or ``@record(eq=False)``."""
    if cls is None:
        return lambda c: _make(c, eq, frozen)
    return _make(cls, eq, frozen)


def _make(cls, eq, frozen):
    if not cls.__dict__.get("__doc__"):
        names = [n for n, t in cls.__dict__.get("__annotations__", {}).items()
                 if "ClassVar" not in str(t)]
        cls.__doc__ = f"{cls.__name__}({', '.join(names)})"
    cls = dataclasses.dataclass(cls, init=False, repr=False, eq=False, frozen=False)
    fields = dataclasses.fields(cls)
    for f in cls.__dataclass_fields__.values():
        if f._field_type is dataclasses._FIELD_INITVAR or getattr(f, "kw_only", False) is True:
            raise TypeError(f"{cls.__qualname__}.{f.name}: @record has no InitVar or kw_only")
    init_fields = [f for f in fields if f.init]
    if "__init__" not in cls.__dict__:
        cls.__init__ = _init(cls, init_fields, [f for f in fields if not f.init])
        cls.__signature__ = _LazySignature(init_fields)
    if "__repr__" not in cls.__dict__:
        cls.__repr__ = _repr(tuple(f.name for f in fields if f.repr))
    if eq and "__eq__" not in cls.__dict__:
        compared = tuple(f.name for f in fields if f.compare)
        cls.__eq__ = _eq(compared)
        if frozen:
            hashed = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
            cls.__hash__ = _hash(hashed)
        else:
            cls.__hash__ = None
    if frozen:
        cls.__setattr__, cls.__delattr__ = _frozen(cls, frozenset(f.name for f in fields))
    return cls


def _init(cls, init_fields, other_fields):
    names = tuple(f.name for f in init_fields)
    known = frozenset(names)
    count = len(names)
    fill = tuple((f.name, f.default, f.default_factory) for f in init_fields
                 if f.default is not _MISSING or f.default_factory is not _MISSING)
    required = tuple(f.name for f in init_fields
                     if f.default is _MISSING and f.default_factory is _MISSING)
    # a field outside __init__ with a plain default is read from the class, as in dataclasses
    later = tuple((f.name, f.default_factory) for f in other_fields
                  if f.default_factory is not _MISSING)
    post_init = hasattr(cls, "__post_init__")
    qualname = cls.__qualname__

    def __init__(self, *args, **kwargs):
        d = self.__dict__
        if args:
            if len(args) > count:
                raise TypeError(f"{qualname}.__init__() takes {count + 1} positional "
                                f"arguments but {len(args) + 1} were given")
            d.update(zip(names, args))
        if kwargs:
            for name in kwargs:
                if name not in known:
                    raise TypeError(f"{qualname}.__init__() got an unexpected keyword "
                                    f"argument {name!r}")
                if name in d:
                    raise TypeError(f"{qualname}.__init__() got multiple values for "
                                    f"argument {name!r}")
            d.update(kwargs)
        if len(d) < count:
            missing = [n for n in required if n not in d]
            if missing:
                raise TypeError(f"{qualname}.__init__() missing {len(missing)} required "
                                f"argument{'s' if len(missing) > 1 else ''}: "
                                + ", ".join(repr(n) for n in missing))
            for name, default, factory in fill:
                if name not in d:
                    d[name] = factory() if default is _MISSING else default
        for name, factory in later:
            d[name] = factory()
        if post_init:
            self.__post_init__()

    __init__.__qualname__ = f"{qualname}.__init__"
    return __init__


class _Factory:
    def __repr__(self):
        return "<factory>"


_FACTORY = _Factory()


class _LazySignature:
    """``cls.__signature__``: the constructor's signature, built when asked for."""

    def __init__(self, init_fields):
        self.fields = init_fields

    def __get__(self, obj, owner=None):
        import inspect
        P = inspect.Parameter
        return inspect.Signature([
            P(f.name, P.POSITIONAL_OR_KEYWORD, annotation=f.type,
              default=(f.default if f.default is not _MISSING
                       else P.empty if f.default_factory is _MISSING else _FACTORY))
            for f in self.fields], return_annotation=None)


def _repr(names):
    @reprlib.recursive_repr()
    def __repr__(self):
        return (f"{type(self).__qualname__}("
                + ", ".join(f"{n}={getattr(self, n)!r}" for n in names) + ")")
    return __repr__


def _eq(names):
    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return tuple(getattr(self, n) for n in names) \
                == tuple(getattr(other, n) for n in names)
        return NotImplemented
    return __eq__


def _hash(names):
    def __hash__(self):
        return hash(tuple(getattr(self, n) for n in names))
    return __hash__


def _frozen(cls, names):
    def __setattr__(self, name, value):
        if type(self) is cls or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)

    def __delattr__(self, name):
        if type(self) is cls or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)
    return __setattr__, __delattr__
