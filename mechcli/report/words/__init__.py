"""The report's wording: one English/Chinese catalogue that every report module looks up.

Every sentence, heading and label a report or figure prints lives here, in one module per
section (``kin.py``, ``force.py``, …, ``common.py`` for words many sections share), each a
``WORDS`` dict of entries::

    "summary": {"en": "Summary", "zh": "汇总"},
    "positions": {"en": "{n} positions analysed", "zh": "共 {n} 个位置"},

and is looked up by ``section.key``::

    from mechcli.report.words import say
    say("zh", "force.summary")               # '汇总'
    say("en", "common.positions", n=361)     # '361 positions analysed'

The placeholders are ``str.format`` fields, the same in both languages (a test checks it); the
numbers are formatted by the caller. A language without its own entry falls back to English, so a
third language is a third key in each entry. Sections are imported on first use: a run loads
only the sections it prints, and as Python (not TOML) they cost no parser at start-up
(``grashof --lengths`` reads no file at all).
"""
from __future__ import annotations

import functools
import importlib
from typing import Dict

__all__ = ["say", "section", "table", "language", "LANGUAGES", "CJK"]

#: the languages every entry carries
LANGUAGES = ("en", "zh")
#: the languages written in Chinese characters (a picture draws their text only with a CJK font)
CJK = frozenset({"zh"})


@functools.cache
def section(name: str) -> Dict[str, Dict[str, str]]:
    """One section of the catalogue: ``{key: {"en": …, "zh": …}}`` (imported once)."""
    words: Dict[str, Dict[str, str]] = importlib.import_module(f"{__name__}.{name}").WORDS
    return words


def say(lang: str, key: str, **fields: object) -> str:
    """The catalogue's text for ``section.key`` in ``lang`` (English if it has none), formatted."""
    name, _, entry = key.partition(".")
    forms = section(name)[entry]
    text = forms.get(lang) or forms["en"]
    return text.format(**fields) if fields else text


def table(lang: str, name: str) -> Dict[str, str]:
    """A whole section in one language, ``{key: text}`` (for modules that look up many labels)."""
    return {k: (v.get(lang) or v["en"]) for k, v in section(name).items()}


def language(lang: object) -> str:
    """A language code from a code or from the older ``zh`` flag of some report helpers
    (True: ``"zh"``, False: ``"en"``)."""
    return LANGUAGES[lang] if isinstance(lang, bool) else str(lang)
