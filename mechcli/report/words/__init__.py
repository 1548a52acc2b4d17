"""The report's wording: one English/Chinese catalogue that every report module looks up.

Every sentence, heading and label a report or figure prints lives here, in one TOML file per
section (``kin.toml``, ``force.toml``, …, ``common.toml`` for words many sections share), as::

    summary = { en = "Summary", zh = "汇总" }
    positions = { en = "{n} positions analysed", zh = "共 {n} 个位置" }

and is looked up by ``section.key``::

    from mechcli.report.words import say
    say("zh", "force.summary")               # '汇总'
    say("en", "common.positions", n=361)     # '361 positions analysed'

The placeholders are ``str.format`` fields, the same in both languages (a test checks it); the
numbers are formatted by the caller. A language without its own entry falls back to English, so a
third language is a third key in each entry. Sections are read on first use and cached: a run
reads only the sections it prints.
"""
from __future__ import annotations

import functools
import sys
from importlib import resources
from typing import Dict

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python < 3.11
    import tomli as tomllib

__all__ = ["say", "section", "table", "LANGUAGES"]

#: the languages every entry carries
LANGUAGES = ("en", "zh")


@functools.cache
def section(name: str) -> Dict[str, Dict[str, str]]:
    """One section of the catalogue: ``{key: {"en": …, "zh": …}}`` (read once, then cached)."""
    text = resources.files(__name__).joinpath(f"{name}.toml").read_text(encoding="utf-8")
    return tomllib.loads(text)


def say(lang: str, key: str, **fields: object) -> str:
    """The catalogue's text for ``section.key`` in ``lang`` (English if it has none), formatted."""
    name, _, entry = key.partition(".")
    forms = section(name)[entry]
    text = forms.get(lang) or forms["en"]
    return text.format(**fields) if fields else text


def table(lang: str, name: str) -> Dict[str, str]:
    """A whole section in one language, ``{key: text}`` (for modules that look up many labels)."""
    return {k: (v.get(lang) or v["en"]) for k, v in section(name).items()}
