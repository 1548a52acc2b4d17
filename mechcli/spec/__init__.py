"""TOML problem files -> validated, frozen dataclasses in SI units."""

from mechcli.spec.errors import SpecError
from mechcli.spec.reader import Section, load_spec

__all__ = ["SpecError", "Section", "load_spec"]
