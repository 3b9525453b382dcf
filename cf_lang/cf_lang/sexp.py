"""S-expression reader and writer with a json-like API: ``loads`` and ``dumps``.

Values map to Python as follows:

======================  =====================================
text                    Python
======================  =====================================
``(a 1 "s")``           ``list``
``foo``, ``a-b``        :class:`Symbol` (a ``str`` subclass)
``:x``                  :class:`Keyword` (its name, no colon)
``"text"``              ``str``
``42``, ``-7``          ``int``
``1.5``, ``-2e-3``      ``float``
======================  =====================================

``; comment`` runs to the end of the line. The reader is iterative (no
recursion, so no RecursionError at any depth) and enforces :class:`Limits`.
Every bad input raises a :class:`~cf_lang.errors.SexpError` that says line,
column, what was expected and what was found.

Speed comes from tokenising with one compiled regular expression (``findall``
runs in C) and building lists in a flat loop. Only when that fast pass fails
does a second, slower pass walk the text again to say exactly where and why.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import SexpError, SexpLimitError, SexpSyntaxError, SexpWriteError

__all__ = ["DEFAULT_LIMITS", "Keyword", "Limits", "Symbol", "dumps", "loads"]

_TOKEN = re.compile(r"""\s*([()]|"[^"\\]*(?:\\.[^"\\]*)*"|;[^\n]*|[^\s()";]+|\S)""")
_findall = _TOKEN.findall
_SYMBOL_RE = re.compile(r"""[^\s()";:][^\s()";]*""")
_NUMBER_RE = re.compile(r"""[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?""")
_INTEGER_RE = re.compile(r"""[-+]?\d+""")
_ESCAPES = {'"': '"', "\\": "\\", "n": "\n", "t": "\t", "r": "\r"}
_ESCAPE_RE = re.compile(r"\\(.)", re.DOTALL)
_BAD_ESCAPE_RE = re.compile(r'\\[^"\\ntr]', re.DOTALL)
_NEEDS_ESCAPE = re.compile(r'["\\\n\r\t]')
_NUMBER_START = frozenset("0123456789+-.")
_MAX_INT_DIGITS = 4000
_new_str = str.__new__


class Symbol(str):
    """A bare word such as ``Player`` or ``exec``.

    It compares equal to the plain ``str`` of the same text, so it works as a
    dict key; use ``type(x) is Symbol`` to tell a symbol from a string.
    """

    __slots__ = ()

    def __new__(cls, name: str) -> Symbol:
        if not isinstance(name, str) or not _SYMBOL_RE.fullmatch(name) or _NUMBER_RE.fullmatch(name):
            raise SexpWriteError(f"not a valid symbol: {name!r}")
        return _new_str(cls, name)

    @property
    def name(self) -> str:
        """The symbol as a plain string."""
        return str(self)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({str.__repr__(self.name)})"

    def __reduce__(self):
        return (type(self), (self.name,))


class Keyword(Symbol):
    """An attribute label such as ``:x``.

    ``Keyword("x") == Keyword(":x")``; the text holds the colon (so writing it
    is free) and ``.name`` gives the name without it.
    """

    __slots__ = ()

    def __new__(cls, name: str) -> Keyword:
        if not isinstance(name, str):
            raise SexpWriteError(f"not a valid keyword: {name!r}")
        bare = name[1:] if name.startswith(":") else name
        if not _SYMBOL_RE.fullmatch(bare):
            raise SexpWriteError(f"not a valid keyword: {name!r}")
        return _new_str(cls, ":" + bare)

    @property
    def name(self) -> str:
        """The keyword without its colon."""
        return str.__str__(self)[1:]


@dataclass(frozen=True)
class Limits:
    """Bounds the reader enforces; the defaults protect a server."""

    max_bytes: int = 1 << 20  # characters for str input, bytes for bytes input
    max_depth: int = 64
    max_atoms: int = 100_000


DEFAULT_LIMITS = Limits()


class _Bad(Exception):
    """Raised inside the fast pass; the slow pass then explains the problem."""


_OPEN = object()
_CLOSE = object()
_SKIP = object()
# Token text -> value for parentheses, symbols and keywords seen before: reading
# a known word is one dict lookup. Bounded, so hostile input cannot grow it.
_ATOMS: dict = {"(": _OPEN, ")": _CLOSE}
_ATOMS_MAX = 50_000
_CACHED_ATOM_LENGTH = 64  # longer atoms are rare words or hostile input: not worth keeping
_atom_get = _ATOMS.get


def _unescape_one(match: re.Match) -> str:
    try:
        return _ESCAPES[match.group(1)]
    except KeyError:
        raise _Bad from None


def unescape(body: str) -> str:
    """The body of a string token, whose escapes were already checked, with the escapes read."""
    return _ESCAPE_RE.sub(_unescape_one, body) if "\\" in body else body


def _classify(tok):
    """Turn one token that is not in the atom cache into its value."""
    if type(tok) is tuple:  # a string body cut out by the fast splitter
        return tok[0]
    first = tok[0]
    if first in _NUMBER_START and "_" not in tok and tok.isascii():
        try:
            if "." in tok or "e" in tok or "E" in tok:
                value = float(tok)
                if value - value != 0.0:  # inf from an exponent such as 1e999
                    raise _Bad
                return value
            if len(tok) > _MAX_INT_DIGITS and len(tok.lstrip("+-")) > _MAX_INT_DIGITS:
                raise _Bad  # the spec's limit (Python's own would allow 4,300)
            return int(tok)
        except ValueError:
            if len(tok) > _MAX_INT_DIGITS and _INTEGER_RE.fullmatch(tok):
                raise _Bad from None
    if first == '"':
        if len(tok) < 2:
            raise _Bad
        body = tok[1:-1]
        return unescape(body)
    if first == ":":
        if len(tok) < 2 or tok[1] == ":":
            raise _Bad
        value = _new_str(Keyword, tok)
    elif first == ";":
        return _SKIP
    else:
        value = _new_str(Symbol, tok)
    if len(tok) <= _CACHED_ATOM_LENGTH and len(_ATOMS) < _ATOMS_MAX:  # bounded in bytes too
        _ATOMS[tok] = value
    return value


def _tokens(text: str) -> list:
    """Split text into tokens; strings become 1-tuples of their body."""
    if "\\" in text or ";" in text:
        return _findall(text)  # escapes or comments: the regex handles them
    # The common case in C: cut out strings at quotes, pad parentheses, split.
    parts = text.split('"')
    if len(parts) == 1:
        return text.replace("(", " ( ").replace(")", " ) ").split()
    if not len(parts) & 1:
        raise _Bad  # an unterminated string
    tokens: list = []
    extend = tokens.extend
    append = tokens.append
    for i, part in enumerate(parts):
        if i & 1:
            append((part,))
        else:
            extend(part.replace("(", " ( ").replace(")", " ) ").split())
    return tokens


def loads(text: str | bytes, *, limits: Limits = DEFAULT_LIMITS):
    """Read exactly one S-expression from ``text``; raise SexpError if it is not one."""
    if isinstance(text, (bytes, bytearray, memoryview)):
        raw = bytes(text)
        if len(raw) > limits.max_bytes:
            raise _limit(
                raw[: limits.max_bytes].decode("utf-8", "replace"), limits.max_bytes, "bytes", len(raw), limits
            )
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            prefix = raw[: exc.start].decode("utf-8", "replace")
            line, col = _line_col(prefix, len(prefix))
            raise SexpSyntaxError(
                "invalid UTF-8",
                line=line,
                column=col,
                offset=exc.start,
                expected="UTF-8 text",
                found=f"byte 0x{raw[exc.start]:02x}",
            ) from None
    elif not isinstance(text, str):
        raise TypeError(f"loads() takes str or bytes, not {type(text).__name__}")
    if len(text) > limits.max_bytes:
        raise _limit(text, limits.max_bytes, "characters", len(text), limits)
    root: list = []
    cur = root
    stack: list = []
    max_depth = limits.max_depth
    get = _atom_get
    try:
        tokens = _tokens(text)
        if len(tokens) > limits.max_atoms:
            raise _Bad
        for tok in tokens:
            value = get(tok)
            if value is None:
                value = _classify(tok)
            if value is _OPEN:
                new: list = []
                cur.append(new)
                stack.append(cur)
                if len(stack) > max_depth:
                    raise _Bad
                cur = new
            elif value is _CLOSE:
                cur = stack.pop()
            elif value is not _SKIP:
                cur.append(value)
    except (_Bad, IndexError):
        _explain(text, limits)
    if stack or len(root) != 1:
        _explain(text, limits)
    return root[0]


def _line_col(text: str, offset: int) -> tuple[int, int]:
    line = text.count("\n", 0, offset) + 1
    return line, offset - (text.rfind("\n", 0, offset) + 1) + 1


def _describe(text: str, offset: int) -> str:
    if offset >= len(text):
        return "end of input"
    return repr(text[offset : offset + 20])


def _error(cls, message: str, text: str, offset: int, expected: str, found: str | None = None):
    line, col = _line_col(text, offset)
    return cls(
        message,
        line=line,
        column=col,
        offset=offset,
        expected=expected,
        found=_describe(text, offset) if found is None else found,
    )


def _limit(text: str, offset: int, what: str, size: int, limits: Limits) -> SexpLimitError:
    return _error(
        SexpLimitError,
        "input too large",
        text,
        min(offset, len(text)),
        f"at most {limits.max_bytes} {what}",
        f"{size} {what}",
    )


def _explain(text: str, limits: Limits) -> None:
    """Walk the text again, slowly, and raise the precise error."""
    opens: list[int] = []
    seen_top = False
    atoms = 0
    for m in _TOKEN.finditer(text):
        tok = m.group(1)
        pos = m.start(1)
        if tok[0] == ";":
            continue
        atoms += 1
        if atoms > limits.max_atoms:
            raise _error(SexpLimitError, "too many atoms", text, pos, f"at most {limits.max_atoms} atoms")
        if not opens and seen_top:
            raise _error(SexpSyntaxError, "trailing content", text, pos, "end of input")
        if tok == "(":
            opens.append(pos)
            if len(opens) > limits.max_depth:
                raise _error(SexpLimitError, "nesting too deep", text, pos, f"at most {limits.max_depth} levels")
            continue
        if tok == ")":
            if not opens:
                raise _error(SexpSyntaxError, "unbalanced ')'", text, pos, "an expression")
            opens.pop()
        elif tok == '"':
            raise _error(SexpSyntaxError, "unterminated string", text, pos, 'a closing "', "end of input")
        else:
            try:
                _classify(tok)
            except _Bad:
                cls, message, expected = _why(tok)
                bad_escape = _BAD_ESCAPE_RE.search(tok) if tok[0] == '"' else None
                at = pos + bad_escape.start() if bad_escape else pos
                raise _error(cls, message, text, at, expected) from None
        if not opens:
            seen_top = True
    if opens:
        raise _error(
            SexpSyntaxError, "unclosed '('", text, len(text), "')'", f"end of input ('(' at offset {opens[-1]})"
        )
    if not seen_top:
        raise _error(SexpSyntaxError, "empty input", text, len(text), "an expression")
    raise _error(SexpSyntaxError, "unreadable input", text, 0, "an S-expression")  # pragma: no cover


def _why(tok: str) -> tuple[type[SexpError], str, str]:
    if tok[0] == '"':
        return SexpSyntaxError, "unknown escape in string", 'only \\" \\\\ \\n \\t \\r'
    if tok[0] == ":":
        return SexpSyntaxError, "bad keyword", "a name after ':'"
    if _INTEGER_RE.fullmatch(tok):
        return SexpLimitError, "integer too long", f"at most {_MAX_INT_DIGITS} digits"
    return SexpSyntaxError, "number out of range", "a finite number"


def quote(value: str) -> str:
    """A string written as an S-expression string token, escapes and all."""
    if _NEEDS_ESCAPE.search(value) is None:
        return f'"{value}"'
    return (
        '"'
        + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\r", "\\r").replace("\t", "\\t")
        + '"'
    )


def _dump_seq(value) -> str:
    # Inlined type dispatch: a function call per atom would cost more than the work.
    out = []
    append = out.append
    for item in value:
        kind = type(item)
        if kind is Symbol or kind is Keyword:
            append(item)
        elif kind is float:
            text = repr(item)
            if text[-1] in "fn":  # inf, -inf, nan
                raise SexpWriteError(f"{text} has no S-expression form")
            append(text)
        elif kind is list:
            append(_dump_seq(item))
        elif kind is int:
            append(repr(item))
        else:
            append(_dump(item))
    return "(" + " ".join(out) + ")"


def _dump(value) -> str:
    kind = type(value)
    if kind is list or kind is tuple:
        return _dump_seq(value)
    if kind is Symbol or kind is Keyword:
        return str.__str__(value)
    if kind is str:
        return quote(value)
    if kind is int:
        return int.__repr__(value)
    if kind is float:
        return _dump_seq([value])[1:-1]
    raise SexpWriteError(f"{kind.__name__} has no S-expression form: {value!r}")


def dumps(value) -> str:
    """Write ``value`` as one line of S-expression text."""
    try:
        return _dump_seq(value) if type(value) is list else _dump(value)
    except RecursionError:
        raise SexpWriteError("value is nested too deeply to write") from None
