"""Typed errors of the Framework Language. Every bad input raises one of these."""

from __future__ import annotations


class LanguageError(ValueError):
    """Base of every error cf_lang raises on bad input."""


class SexpError(LanguageError):
    """The text is not a well-formed S-expression, or breaks a limit.

    Carries where (1-based line and column, 0-based offset), what the reader
    expected there and what it found.
    """

    def __init__(self, message: str, *, line: int, column: int, offset: int, expected: str, found: str):
        super().__init__(f"{message} at line {line}, column {column}: expected {expected}, found {found}")
        self.line = line
        self.column = column
        self.offset = offset
        self.expected = expected
        self.found = found


class SexpSyntaxError(SexpError):
    """Malformed text: unbalanced parentheses, bad string escape, invalid UTF-8."""


class SexpLimitError(SexpError):
    """The input is larger, deeper or has more atoms than the reader allows."""


class SexpWriteError(LanguageError):
    """A Python value that has no S-expression form (a bool, NaN, a dict, ...)."""


class ExpressionError(LanguageError):
    """A well-formed S-expression that is not a valid Framework Language expression.

    ``problems`` lists every problem found as ``(path, message)`` pairs; a path
    names the place in the expression, e.g. ``Player.positioning.x``.
    """

    def __init__(self, problems: list[tuple[str, str]]):
        self.problems = list(problems)
        super().__init__("; ".join(f"{path or '<root>'}: {msg}" for path, msg in self.problems))


class AclError(LanguageError):
    """A FIPA-ACL message that cannot be read or is missing what it needs."""


class ProtocolError(LanguageError):
    """A message or action that the conversation protocol does not allow now."""
