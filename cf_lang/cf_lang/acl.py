"""FIPA-ACL messages (FIPA SC00061) and their string form (FIPA SC00070).

    (request
      :sender (agent-identifier :name blue_3_decision)
      :receiver (set (agent-identifier :name blue_3_action))
      :content "(exec Player kick :playerNumber 3 :whichTeam our :power 80 :direction 0.1)"
      :language cf-lang :ontology robocup-soccer :protocol fipa-request
      :conversation-id c42 :reply-with r1 :reply-by 20261122T101010123Z)

Performatives and parameter names are read case-insensitively. ``reply-by``
is a FIPA date-time (``YYYYMMDDTHHMMSSmmm``, a trailing ``Z`` for UTC; times
without it are read as UTC too) and is held as seconds since the epoch. The
content is a string holding Framework Language; a Prolog agent may also write
it as a bare S-expression, which is read and kept as text.
"""

from __future__ import annotations

import calendar
import re
import time
from enum import StrEnum
from typing import NamedTuple

from . import acl_fast
from .errors import AclError, SexpError
from .ontology import LANGUAGE, ONTOLOGY
from .sexp import DEFAULT_LIMITS, Keyword, Limits, Symbol, dumps, loads, quote, unescape


class Performative(StrEnum):
    """The 22 FIPA communicative acts."""

    ACCEPT_PROPOSAL = "accept-proposal"
    AGREE = "agree"
    CANCEL = "cancel"
    CFP = "cfp"
    CONFIRM = "confirm"
    DISCONFIRM = "disconfirm"
    FAILURE = "failure"
    INFORM = "inform"
    INFORM_IF = "inform-if"
    INFORM_REF = "inform-ref"
    NOT_UNDERSTOOD = "not-understood"
    PROPAGATE = "propagate"
    PROPOSE = "propose"
    PROXY = "proxy"
    QUERY_IF = "query-if"
    QUERY_REF = "query-ref"
    REFUSE = "refuse"
    REJECT_PROPOSAL = "reject-proposal"
    REQUEST = "request"
    REQUEST_WHEN = "request-when"
    REQUEST_WHENEVER = "request-whenever"
    SUBSCRIBE = "subscribe"


_PERFORMATIVES = {p.value: p for p in Performative}


class AgentId(NamedTuple):
    """An agent identifier: a unique name and the transport addresses it listens on."""

    name: str
    addresses: tuple[str, ...] = ()

    def to_sexp(self) -> list:
        out: list = [_AID, _K_NAME, _word(self.name)]
        if self.addresses:
            out += [_K_ADDRESSES, [_SEQUENCE, *(_word(a) for a in self.addresses)]]
        return out


class AclMessage(NamedTuple):
    """One FIPA-ACL message. ``reply_by`` is epoch seconds (UTC).

    Immutable. A named tuple rather than a frozen dataclass: every message read
    or sent builds one, and a tuple is built five times faster.
    """

    performative: Performative
    sender: AgentId | None = None
    receivers: tuple[AgentId, ...] = ()
    content: str | None = None
    reply_to: tuple[AgentId, ...] = ()
    language: str | None = LANGUAGE
    encoding: str | None = None
    ontology: str | None = ONTOLOGY
    protocol: str | None = None
    conversation_id: str | None = None
    reply_with: str | None = None
    in_reply_to: str | None = None
    reply_by: float | None = None
    user: tuple[tuple[str, str], ...] = ()
    """User-defined parameters as (name, value) pairs; names start with ``X-``."""

    def __str__(self) -> str:
        return to_text(self)

    def reply(
        self, performative: Performative | str, content: str | None = None, *, sender: AgentId | None = None
    ) -> AclMessage:
        """A reply in the same conversation, addressed to reply-to or the sender."""
        to = self.reply_to or ((self.sender,) if self.sender else ())
        return AclMessage(
            performative=Performative(performative),
            sender=sender if sender is not None else (self.receivers[0] if self.receivers else None),
            receivers=to,
            content=content,
            language=self.language,
            ontology=self.ontology,
            protocol=self.protocol,
            conversation_id=self.conversation_id,
            in_reply_to=self.reply_with,
        )

    def with_(self, **changes) -> AclMessage:
        """A copy with some parameters changed."""
        return self._replace(**changes)


_AID = Symbol("agent-identifier")
_SET = Symbol("set")
_SEQUENCE = Symbol("sequence")
_K_NAME = Keyword("name")
_K_ADDRESSES = Keyword("addresses")
_K_RESOLVERS = Keyword("resolvers")
_WORD_RE = re.compile(r"""[^\s()"#0-9:;+.-][^\s()";]*""")  # never a number to the reader


def _word(text: str):
    """A FIPA word if the text is one, else a string (so it reads back the same)."""
    word = _WORDS.get(text)
    if word is not None:
        return word
    word = str.__new__(Symbol, text) if _WORD_RE.fullmatch(text) else text
    if len(_WORDS) < 4096 and len(text) <= 128:  # agent names, languages, protocols: a few, again and again
        _WORDS[text] = word
    return word


_WORDS: dict[str, object] = {}


# ---- date-times ---------------------------------------------------------------

_DATETIME_RE = re.compile(r"([+-])?(\d{4})(\d{2})(\d{2})T(\d{2})(\d{2})(\d{2})(\d{3})([a-zA-Z])?")


def format_datetime(epoch: float) -> str:
    """Epoch seconds as a FIPA UTC date-time, e.g. ``20261122T101010123Z``."""
    millis = round(epoch * 1000)
    tm = time.gmtime(millis // 1000)
    return time.strftime("%Y%m%dT%H%M%S", tm) + f"{millis % 1000:03d}Z"


def parse_datetime(text: str) -> float:
    """A FIPA date-time as epoch seconds; raises AclError if it is not one."""
    m = _DATETIME_RE.fullmatch(text)
    if not m or m.group(1):
        raise AclError(f"reply-by: expected a date-time like 20261122T101010123Z, found {text!r}")
    year, mon, day, hh, mm, ss, ms = (int(g) for g in m.groups()[1:8])
    try:
        tm = time.struct_time((year, mon, day, hh, mm, ss, 0, 0, 0))
        if not (1 <= mon <= 12 and 1 <= day <= 31 and hh < 24 and mm < 60 and ss < 61):
            raise ValueError
        return (calendar.timegm(tm) * 1000 + ms) / 1000.0
    except (ValueError, OverflowError):
        raise AclError(f"reply-by: not a valid date-time: {text!r}") from None


# ---- writing ------------------------------------------------------------------


_K_SENDER = Keyword("sender")
_K_RECEIVER = Keyword("receiver")
_K_REPLY_TO = Keyword("reply-to")
_K_CONTENT = Keyword("content")
_K_REPLY_BY = Keyword("reply-by")
_K_LANGUAGE = Keyword("language")
_K_ENCODING = Keyword("encoding")
_K_ONTOLOGY = Keyword("ontology")
_K_PROTOCOL = Keyword("protocol")
_K_CONVERSATION_ID = Keyword("conversation-id")
_K_REPLY_WITH = Keyword("reply-with")
_K_IN_REPLY_TO = Keyword("in-reply-to")


def to_sexp(msg: AclMessage, *, sender: AgentId | None = None) -> list:
    """The message as an S-expression; ``sender`` is written if the message has none."""
    # Messages are written on every send: keywords are built once, not per message.
    out: list = [str.__new__(Symbol, msg.performative.value)]
    sender = msg.sender or sender
    if sender is not None:
        out += [_K_SENDER, sender.to_sexp()]
    if msg.receivers:
        out += [_K_RECEIVER, [_SET, *(r.to_sexp() for r in msg.receivers)]]
    if msg.reply_to:
        out += [_K_REPLY_TO, [_SET, *(r.to_sexp() for r in msg.reply_to)]]
    if msg.content is not None:
        out += [_K_CONTENT, msg.content]
    for keyword, value in (
        (_K_LANGUAGE, msg.language),
        (_K_ENCODING, msg.encoding),
        (_K_ONTOLOGY, msg.ontology),
        (_K_PROTOCOL, msg.protocol),
        (_K_CONVERSATION_ID, msg.conversation_id),
        (_K_REPLY_WITH, msg.reply_with),
        (_K_IN_REPLY_TO, msg.in_reply_to),
    ):
        if value is not None:
            out += [keyword, _word(value)]
    if msg.reply_by is not None:
        out += [_K_REPLY_BY, str.__new__(Symbol, format_datetime(msg.reply_by))]
    for name, value in msg.user:
        out += [Keyword(name), value]
    return out


def to_text(msg: AclMessage, *, sender: AgentId | None = None) -> str:
    """The message in FIPA's string form, on one line (``sender`` as in :func:`to_sexp`)."""
    if type(msg.content) is str or msg.content is None:
        # Written straight into one string, without building the lists first: the
        # same text as dumps(to_sexp(...)) (tests check), a third of the time.
        return _write(msg, msg.sender or sender)
    return dumps(to_sexp(msg, sender=sender))


_OPENINGS = {p: f"({p.value}" for p in Performative}
_AGENT_TEXTS: dict[AgentId, str] = {}
# In to_sexp's order: (label, index of the field in AclMessage).
_TEXT_PARAMS = tuple(
    (f" :{name.replace('_', '-')} ", AclMessage._fields.index(name))
    for name in ("language", "encoding", "ontology", "protocol", "conversation_id", "reply_with", "in_reply_to")
)


def _agent_text(agent: AgentId) -> str:
    text = _AGENT_TEXTS.get(agent)
    if text is None:
        text = dumps(agent.to_sexp())
        if len(_AGENT_TEXTS) < 4096 and len(agent.name) <= 128:  # the team's agents, again and again
            _AGENT_TEXTS[agent] = text
    return text


def _write(msg: AclMessage, sender: AgentId | None) -> str:
    parts = [_OPENINGS[msg.performative]]
    append = parts.append
    if sender is not None:
        append(" :sender " + _agent_text(sender))
    if msg.receivers:
        append(" :receiver (set " + " ".join([_agent_text(r) for r in msg.receivers]) + ")")
    if msg.reply_to:
        append(" :reply-to (set " + " ".join([_agent_text(r) for r in msg.reply_to]) + ")")
    if msg.content is not None:
        append(" :content " + quote(msg.content))
    for label, index in _TEXT_PARAMS:
        value = msg[index]
        if value is not None:
            word = _word(value)
            append(label + (word if type(word) is Symbol else quote(word)))
    if msg.reply_by is not None:
        append(" :reply-by " + format_datetime(msg.reply_by))
    for name, value in msg.user:
        append(f" {Keyword(name)} {dumps(value)}")
    append(")")
    return "".join(parts)


# ---- reading ------------------------------------------------------------------

_STRING_PARAMS = {
    "language": "language",
    "encoding": "encoding",
    "ontology": "ontology",
    "protocol": "protocol",
    "conversation-id": "conversation_id",
    "reply-with": "reply_with",
    "in-reply-to": "in_reply_to",
}


def _text_of(value, param: str) -> str:
    if type(value) is list:
        raise AclError(f":{param}: expected a word or string, found a list")
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _agent(value, param: str) -> AgentId:
    if type(value) is list and len(value) == 3 and value[0] == "agent-identifier" and value[1] == _K_NAME:
        name = value[2]  # the common form, (agent-identifier :name x), read without the general loop
        if type(value[1]) is Keyword and (type(name) is Symbol or (type(name) is str and name)):
            return AgentId(str.__str__(name))
    if type(value) is Symbol or type(value) is str:
        return AgentId(str(value))  # a bare name, accepted for convenience
    if type(value) is not list or not value or str(value[0]).lower() != "agent-identifier":
        raise AclError(f":{param}: expected (agent-identifier :name ...), found {dumps_safe(value)}")
    name = None
    addresses: tuple[str, ...] = ()
    items = value[1:]
    if len(items) % 2:
        raise AclError(f":{param}: agent-identifier needs :parameter value pairs")
    for i in range(0, len(items), 2):
        label, item = items[i], items[i + 1]
        key = label.name.lower() if type(label) is Keyword else None
        if key == "name":
            name = _text_of(item, f"{param} name")
        elif key == "addresses":
            if type(item) is not list or not item or str(item[0]).lower() != "sequence":
                raise AclError(f":{param}: :addresses must be (sequence url ...)")
            addresses = tuple(_text_of(a, f"{param} address") for a in item[1:])
        elif key == "resolvers" or (key and key.startswith("x-")):
            continue
        else:
            raise AclError(f":{param}: unknown agent-identifier parameter {dumps_safe(label)}")
    if not name:
        raise AclError(f":{param}: agent-identifier without :name")
    return AgentId(name, addresses)


def _agents(value, param: str) -> tuple[AgentId, ...]:
    if type(value) is list and value and type(value[0]) is Symbol and str(value[0]).lower() in ("set", "sequence"):
        return tuple(_agent(v, param) for v in value[1:])
    return (_agent(value, param),)


def dumps_safe(value) -> str:
    try:
        text = dumps(value)
    except Exception:
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def from_sexp(sexp) -> AclMessage:
    """Build a message from an already-read S-expression."""
    if type(sexp) is not list or not sexp or type(sexp[0]) is not Symbol:
        raise AclError(f"expected (performative :parameter value ...), found {dumps_safe(sexp)}")
    perf = _PERFORMATIVES.get(str(sexp[0]).lower())
    if perf is None:
        raise AclError(f"unknown performative {sexp[0]!s}; expected one of the 22 FIPA acts")
    items = sexp[1:]
    if len(items) % 2:
        raise AclError("expected :parameter value pairs after the performative")
    fields: dict = {"performative": perf, "language": None, "ontology": None}
    user: list[tuple[str, str]] = []
    seen: set[str] = set()
    for i in range(0, len(items), 2):
        label, value = items[i], items[i + 1]
        if type(label) is not Keyword:
            raise AclError(f"expected a :parameter, found {dumps_safe(label)}")
        name = label[1:].lower()
        if name in seen:
            raise AclError(f":{name} given twice")
        seen.add(name)
        if name == "sender":
            fields["sender"] = _agent(value, name)
        elif name == "receiver":
            fields["receivers"] = _agents(value, name)
        elif name == "reply-to":
            fields["reply_to"] = _agents(value, name)
        elif name == "content":
            fields["content"] = value if type(value) is str else dumps(value)
        elif name in _STRING_PARAMS:
            fields[_STRING_PARAMS[name]] = _text_of(value, name)
        elif name == "reply-by":
            fields["reply_by"] = parse_datetime(_text_of(value, name))
        elif name.startswith("x-"):
            user.append((label.name, _text_of(value, name)))
        else:
            raise AclError(f"unknown message parameter :{label.name}")
    fields["user"] = tuple(user)
    return AclMessage(**fields)


def parse(text: str | bytes, *, limits: Limits = DEFAULT_LIMITS) -> AclMessage:
    """Read a message in FIPA's string form; raise SexpError or AclError."""
    if type(text) is str:
        found = acl_fast.split(text, limits)
        if found is not None:  # the common shape, checked in C: the same message in about half the time
            performative = _PERFORMATIVES.get(found[0].lower())
            if performative is not None:
                return _from_pairs(performative, found[2])
    return from_sexp(loads(text, limits=limits))


def _from_pairs(performative: Performative, pairs: list[tuple[str, str]]) -> AclMessage:
    """The message :func:`acl_fast.split` found: every value there is checked already."""
    values = _READ_DEFAULTS.copy()
    values[0] = performative
    for key, value in pairs:
        index = _FIELD_INDEX[key]
        if index in (_RECEIVERS, _REPLY_TO):
            values[index] = _agents_in(value)
        elif index == _SENDER:
            values[index] = _agents_in(value)[0]
        elif index == _REPLY_BY:
            values[index] = parse_datetime(value)
        else:  # content and the word-valued parameters
            values[index] = unescape(value[1:-1]) if value[0] == '"' else value
    return _new_message(AclMessage, values)


# The message tuple is built here directly: parameter name -> index of its field,
# and each field as a message read without that parameter has it.
_FIELD_INDEX = {
    **{name.replace("_", "-"): i for i, name in enumerate(AclMessage._fields)},
    "receiver": AclMessage._fields.index("receivers"),
}
_SENDER, _RECEIVERS, _REPLY_TO, _REPLY_BY = (_FIELD_INDEX[k] for k in ("sender", "receiver", "reply-to", "reply-by"))
_READ_DEFAULTS = [
    None if f in ("language", "ontology") else AclMessage._field_defaults.get(f) for f in AclMessage._fields
]
_new_message = tuple.__new__
_AGENT_LISTS: dict[str, tuple[AgentId, ...]] = {}


def _agents_in(value: str) -> tuple[AgentId, ...]:
    """The agents in an agent-identifier or set text; the same few teammates come again and again."""
    agents = _AGENT_LISTS.get(value)
    if agents is None:
        agents = tuple(AgentId(name) for name in acl_fast.names(value))
        if len(_AGENT_LISTS) < 4096 and len(value) <= 1024:
            _AGENT_LISTS[value] = agents
    return agents


def check_content(msg: AclMessage) -> None:
    """Raise AclError unless the message's language and ontology are ours (or unset)."""
    if msg.language not in (None, LANGUAGE):
        raise AclError(f"content language {msg.language!r} is not understood; use {LANGUAGE}")
    if msg.ontology not in (None, ONTOLOGY):
        raise AclError(f"ontology {msg.ontology!r} is not understood; use {ONTOLOGY}")


__all__ = [
    "AclMessage",
    "AgentId",
    "Performative",
    "SexpError",
    "check_content",
    "format_datetime",
    "from_sexp",
    "parse",
    "parse_datetime",
    "to_sexp",
    "to_text",
]
