"""A fast reader for ACL messages of the common one-line shape, one regular expression run in C.

The full reader (``loads`` then ``acl.from_sexp``) builds every nested list
and checks every parameter in Python. Almost every message on the wire has
one simple shape, though::

    (request :sender (agent-identifier :name a) :receiver (set (agent-identifier :name b))
      :content "..." :protocol fipa-request :conversation-id c1)

:func:`split` recognises exactly that shape (sender, receiver, reply-to,
content, reply-by and the word-valued parameters; names of the form agent names take;
lower-case parameter names; one line) with one ``fullmatch``, and gives
``None`` for anything else, which the full reader then reads or explains.
It never accepts a text the full reader rejects: tests check this on
generated and mutated messages.
"""

from __future__ import annotations

import re

from .sexp import Limits

# Atomic groups (?>...) keep the match from backtracking into hostile text. Not the possessive
# quantifiers (*+ ++) that say the same: before Python 3.11.5 (CPython gh-106052; Debian 12 has
# 3.11.2) they matched where the plain quantifier does not, and this reader took a malformed
# reply-to for a good one.
_SP = r"(?>[ \t]+)"
_OSP = r"(?>[ \t]*)"
_NAME = r"[A-Za-z](?>[A-Za-z0-9_]*)"
_AID = rf"\({_OSP}agent-identifier{_SP}:name{_SP}{_NAME}{_OSP}\)"
_SET = rf"\({_OSP}set(?>(?:{_SP}{_AID})+){_OSP}\)"
# Only the escapes the reader knows. A word is what the reader takes for a symbol:
# not a number (+ - . digits), keyword (:), comment (;), string or parenthesis.
_STR = r'"(?>(?:(?>[^"\\]+)|\\["\\ntr])*)"'
_WORD = r"""[^\s()";:0-9+.\-](?>[^\s()";]*)"""
_TEXT_KEYS = "language|encoding|ontology|protocol|conversation-id|reply-with|in-reply-to"
# A FIPA date-time; the caller checks the date itself (parse_datetime).
_TIME = r"[0-9]{8}T[0-9]{9}(?>[A-Za-z]?)"
_PARAM = (
    rf"{_SP}(?::sender{_SP}{_AID}|:(?:receiver|reply-to){_SP}{_SET}|:content{_SP}{_STR}"
    rf"|:(?:{_TEXT_KEYS}){_SP}(?:{_WORD}|{_STR})|:reply-by{_SP}{_TIME})"
)
# The performative is any word here; the caller checks it is one of the 22.
_MESSAGE = re.compile(rf"{_OSP}\({_OSP}([A-Za-z](?>[A-Za-z-]*))((?>(?:{_PARAM})*)){_OSP}\){_OSP}")
_PAIRS = re.compile(rf"{_SP}:((?>[a-z-]+)){_SP}({_SET}|{_AID}|{_STR}|{_WORD}|{_TIME})")
_NAMES = re.compile(rf":name{_SP}({_NAME})")

_fullmatch = _MESSAGE.fullmatch
_findall = _PAIRS.findall
names = _NAMES.findall
"""The agent names in a ``(set ...)`` or ``(agent-identifier ...)`` value from :func:`split`."""


def split(text: str, limits: Limits) -> tuple[str, int, list[tuple[str, str]]] | None:
    """``(performative as written, where it ends, [(parameter, value text), ...])``, or None.

    Two things are left to the caller: whether the performative is one of the
    22 (read the text fully if not), and whether a ``reply-by`` date exists.

    None when the text is not of the common shape, a parameter is given
    twice, or the limits are tighter than the shape needs: the full reader
    decides then.
    """
    # The shape nests 3 deep and has fewer atoms than characters.
    if len(text) > limits.max_bytes or limits.max_depth < 3 or len(text) > limits.max_atoms:
        return None
    m = _fullmatch(text)
    if m is None:
        return None
    pairs = _findall(m.group(2))
    if len(pairs) > 1 and len({key for key, _ in pairs}) != len(pairs):
        return None
    return m.group(1), m.end(1), pairs
