"""FIPA interaction protocols as small state machines with an injected clock.

Supported: ``fipa-request``, ``fipa-query`` and ``fipa-subscribe``, each for the
initiator and the responder. A :class:`Conversation` knows which performatives
each side may send or receive in its current state; anything else raises
:class:`~cf_lang.errors.ProtocolError`, and :func:`not_understood` builds the
answer to give. Deadlines come from ``reply-by``: the initiator's
:meth:`Conversation.expired` turns a missed one into the ``timed-out`` state.

A :class:`ConversationTable` correlates incoming messages with conversations
by ``conversation-id`` (and checks ``in-reply-to`` against the ``reply-with``
it sent), so an agent can run many conversations at once.

Nothing here does I/O or reads a clock: callers pass ``now`` (seconds).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from enum import StrEnum

from .acl import AclMessage, AgentId, Performative
from .errors import ProtocolError

P = Performative


class ConversationRole(StrEnum):
    INITIATOR = "initiator"
    RESPONDER = "responder"


@dataclass(frozen=True)
class ProtocolSpec:
    """States and the performatives that move between them.

    ``initiator_moves[state][performative] = next_state`` for what the
    initiator sends (outgoing) or receives (incoming); likewise for the responder.
    Terminal states have no moves.
    """

    name: str
    opening: frozenset[Performative]
    moves: dict[str, dict[Performative, str]]
    """state -> performative -> next state; who may send it is in ``senders``."""
    senders: dict[Performative, ConversationRole]


_ANSWERS = {P.AGREE: "agreed", P.REFUSE: "refused", P.FAILURE: "failed", P.NOT_UNDERSTOOD: "not-understood"}

REQUEST = ProtocolSpec(
    name="fipa-request",
    opening=frozenset({P.REQUEST}),
    moves={
        "start": {P.REQUEST: "requested"},
        # FIPA lets the responder skip agree and answer at once.
        "requested": {**_ANSWERS, P.INFORM: "done"},
        "agreed": {P.INFORM: "done", P.FAILURE: "failed"},
    },
    senders={
        P.REQUEST: ConversationRole.INITIATOR,
        P.AGREE: ConversationRole.RESPONDER,
        P.REFUSE: ConversationRole.RESPONDER,
        P.FAILURE: ConversationRole.RESPONDER,
        P.NOT_UNDERSTOOD: ConversationRole.RESPONDER,
        P.INFORM: ConversationRole.RESPONDER,
    },
)

QUERY = ProtocolSpec(
    name="fipa-query",
    opening=frozenset({P.QUERY_REF, P.QUERY_IF}),
    moves={
        "start": {P.QUERY_REF: "queried", P.QUERY_IF: "queried"},
        "queried": {**_ANSWERS, P.INFORM: "done"},
        "agreed": {P.INFORM: "done", P.FAILURE: "failed"},
    },
    senders={
        P.QUERY_REF: ConversationRole.INITIATOR,
        P.QUERY_IF: ConversationRole.INITIATOR,
        P.AGREE: ConversationRole.RESPONDER,
        P.REFUSE: ConversationRole.RESPONDER,
        P.FAILURE: ConversationRole.RESPONDER,
        P.NOT_UNDERSTOOD: ConversationRole.RESPONDER,
        P.INFORM: ConversationRole.RESPONDER,
    },
)

SUBSCRIBE = ProtocolSpec(
    name="fipa-subscribe",
    opening=frozenset({P.SUBSCRIBE}),
    moves={
        "start": {P.SUBSCRIBE: "subscribing"},
        "subscribing": {
            P.AGREE: "subscribed",
            P.REFUSE: "refused",
            P.NOT_UNDERSTOOD: "not-understood",
            P.FAILURE: "failed",
            P.INFORM: "subscribed",
            P.CANCEL: "cancelling",
        },
        "subscribed": {P.INFORM: "subscribed", P.FAILURE: "failed", P.CANCEL: "cancelling"},
        # After cancel, informs already in flight may still arrive; inform or failure from the
        # responder closes it.
        "cancelling": {P.INFORM: "cancelled", P.FAILURE: "cancelled"},
    },
    senders={
        P.SUBSCRIBE: ConversationRole.INITIATOR,
        P.CANCEL: ConversationRole.INITIATOR,
        P.AGREE: ConversationRole.RESPONDER,
        P.REFUSE: ConversationRole.RESPONDER,
        P.FAILURE: ConversationRole.RESPONDER,
        P.NOT_UNDERSTOOD: ConversationRole.RESPONDER,
        P.INFORM: ConversationRole.RESPONDER,
    },
)

PROTOCOLS = {spec.name: spec for spec in (REQUEST, QUERY, SUBSCRIBE)}
_DEFAULT_OPENING = {REQUEST.name: P.REQUEST, QUERY.name: P.QUERY_REF, SUBSCRIBE.name: P.SUBSCRIBE}
TERMINAL = frozenset({"done", "refused", "failed", "not-understood", "cancelled", "timed-out"})
_ids = itertools.count(1)


def new_conversation_id(owner: str) -> str:
    """A conversation id unique within this process for ``owner``."""
    return f"{owner}-c{next(_ids)}"


class Conversation:
    """One side of one conversation."""

    def __init__(
        self,
        spec: ProtocolSpec,
        role: ConversationRole,
        *,
        me: AgentId,
        peer: AgentId,
        conversation_id: str,
        reply_by: float | None = None,
        deadline: float | None = None,
    ):
        self.spec = spec
        self.role = role
        self.me = me
        self.peer = peer
        self.conversation_id = conversation_id
        self.reply_by = reply_by  # wall-clock epoch seconds: what the opening message carries
        self.deadline = deadline  # the same moment on the caller's own clock (the ``now`` it passes)
        self.state = "start"
        self.history: list[AclMessage] = []
        self._reply_with: str | None = None
        self._last_received: AclMessage | None = None
        self._replies = itertools.count(1)

    @property
    def finished(self) -> bool:
        return self.state in TERMINAL

    def _move(self, performative: Performative, sender_role: ConversationRole) -> str:
        allowed = self.spec.moves.get(self.state, {})
        nxt = allowed.get(performative)
        if nxt is None or self.spec.senders.get(performative) is not sender_role:
            who = "we" if sender_role is self.role else "the peer"
            expected = [p.value for p, _ in allowed.items() if self.spec.senders.get(p) is sender_role]
            raise ProtocolError(
                f"{self.spec.name}: {who} cannot send {performative.value} in state {self.state}"
                f" (expected {', '.join(expected) or 'nothing, the conversation is over'})"
            )
        return nxt

    def send(self, performative: Performative | str, content: str | None = None, *, now: float) -> AclMessage:
        """Build the next outgoing message and advance; raise ProtocolError if not allowed."""
        perf = Performative(performative)
        nxt = self._move(perf, self.role)
        base = self._last_received
        reply_with = f"{self.conversation_id}-r{next(self._replies)}"
        msg = AclMessage(
            performative=perf,
            sender=self.me,
            receivers=(base.reply_to or (self.peer,)) if base is not None else (self.peer,),
            content=content,
            protocol=self.spec.name,
            conversation_id=self.conversation_id,
            reply_with=reply_with,
            in_reply_to=base.reply_with if base is not None else None,
            reply_by=self.reply_by if self.role is ConversationRole.INITIATOR and perf in self.spec.opening else None,
        )
        self._reply_with = reply_with
        self.state = nxt
        self.history.append(msg)
        return msg

    def receive(self, msg: AclMessage, *, now: float) -> str:
        """Take an incoming message, advance and return the new state.

        Raises ProtocolError for a message this side must not get now, or one
        answering a message we did not send (``in-reply-to`` mismatch).
        """
        if msg.conversation_id != self.conversation_id:
            raise ProtocolError(
                f"message belongs to conversation {msg.conversation_id!r}, not {self.conversation_id!r}"
            )
        if self.role is ConversationRole.INITIATOR and msg.in_reply_to is not None and self._reply_with is not None:
            sent = {m.reply_with for m in self.history if m.sender == self.me}
            if msg.in_reply_to not in sent:
                raise ProtocolError(f"in-reply-to {msg.in_reply_to!r} answers nothing we sent")
        peer_role = (
            ConversationRole.RESPONDER if self.role is ConversationRole.INITIATOR else ConversationRole.INITIATOR
        )
        self.state = self._move(msg.performative, peer_role)
        self._last_received = msg
        self.history.append(msg)
        return self.state

    def expired(self, now: float) -> bool:
        """True (and the state becomes timed-out) if a reply is overdue.

        Only the initiator waits; a subscription that was agreed waits for
        nothing, so it never times out here.
        """
        if self.finished or self.deadline is None or self.role is not ConversationRole.INITIATOR:
            return False
        if self.state in ("subscribed",):
            return False
        if now > self.deadline:
            self.state = "timed-out"
            return True
        return False


def initiate(
    protocol: str,
    *,
    me: AgentId,
    peer: AgentId,
    performative: Performative | str | None = None,
    content: str,
    now: float,
    wall: float | None = None,
    timeout: float | None = None,
    conversation_id: str | None = None,
) -> tuple[Conversation, AclMessage]:
    """Open a conversation as initiator; return it and the first message to send.

    ``now`` is the caller's clock (monotonic is best), against which :meth:`Conversation.expired`
    is later asked. ``wall`` is the wall-clock time (epoch seconds, UTC) at that same moment: a
    ``timeout`` puts ``:reply-by wall + timeout`` on the wire, since a FIPA peer reads reply-by as
    a date. It is required with a timeout, so a monotonic reading never reaches the wire.
    """
    spec = PROTOCOLS.get(protocol)
    if spec is None:
        raise ProtocolError(f"unknown protocol {protocol!r}; known: {', '.join(PROTOCOLS)}")
    if timeout is not None and wall is None:
        raise ValueError("a timeout needs wall= (the wall-clock time at now) for the :reply-by on the wire")
    perf = Performative(performative) if performative else _DEFAULT_OPENING[spec.name]
    conv = Conversation(
        spec,
        ConversationRole.INITIATOR,
        me=me,
        peer=peer,
        conversation_id=conversation_id or new_conversation_id(me.name),
        reply_by=None if timeout is None else wall + timeout,
        deadline=None if timeout is None else now + timeout,
    )
    return conv, conv.send(perf, content, now=now)


def respond(msg: AclMessage, *, me: AgentId, now: float) -> Conversation:
    """Open the responder side for an incoming opening message."""
    spec = PROTOCOLS.get(msg.protocol or "") or next(
        (s for s in PROTOCOLS.values() if msg.performative in s.opening), None
    )
    if spec is None or msg.performative not in spec.opening:
        raise ProtocolError(f"{msg.performative.value} does not open a conversation we support")
    if msg.sender is None:
        raise ProtocolError("an opening message needs a :sender")
    if not msg.conversation_id:
        raise ProtocolError("an opening message needs a :conversation-id")
    conv = Conversation(
        spec,
        ConversationRole.RESPONDER,
        me=me,
        peer=msg.sender,
        conversation_id=msg.conversation_id,
        reply_by=msg.reply_by,
    )
    conv.receive(msg, now=now)
    return conv


def not_understood(msg: AclMessage, reason: str, *, me: AgentId) -> AclMessage:
    """The answer to a message we cannot take: not-understood, with the reason."""
    from .sexp import dumps

    content = dumps([[Performative(msg.performative).value, msg.conversation_id or ""], reason])
    return msg.reply(Performative.NOT_UNDERSTOOD, content, sender=me)


class ConversationTable:
    """The conversations of one agent, keyed by conversation-id."""

    def __init__(self) -> None:
        self._by_id: dict[str, Conversation] = {}

    def __len__(self) -> int:
        return len(self._by_id)

    def __contains__(self, conversation_id: object) -> bool:
        return conversation_id in self._by_id

    def add(self, conv: Conversation) -> Conversation:
        if conv.conversation_id in self._by_id:
            raise ProtocolError(f"conversation {conv.conversation_id!r} already exists")
        self._by_id[conv.conversation_id] = conv
        return conv

    def get(self, conversation_id: str) -> Conversation | None:
        return self._by_id.get(conversation_id)

    def dispatch(self, msg: AclMessage, *, now: float) -> Conversation:
        """Hand a message to its conversation; raise ProtocolError if it has none."""
        conv = self._by_id.get(msg.conversation_id or "")
        if conv is None:
            raise ProtocolError(f"no open conversation {msg.conversation_id!r}")
        conv.receive(msg, now=now)
        if conv.finished:
            del self._by_id[conv.conversation_id]
        return conv

    def discard(self, conversation_id: str) -> None:
        self._by_id.pop(conversation_id, None)

    def expire(self, now: float) -> list[Conversation]:
        """Remove and return the conversations whose reply deadline passed."""
        gone = [c for c in self._by_id.values() if c.expired(now)]
        for conv in gone:
            del self._by_id[conv.conversation_id]
        return gone
