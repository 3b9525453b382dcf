"""The agent: what makes an rclpy node a component of the Common Framework.

    node = rclpy.create_node("blue_7_action")
    agent = Agent(node, name="blue_7_action", service_class="Action", team="blue", player_number=7)
    agent.serve("fipa-request", on_request)        # answer requests
    future = agent.request("blue_7_perception", "(val Game time)", protocol="fipa-query")

An :class:`Agent` registers with the ComMAg and renews its lease
(three times per lease, so one late renewal is not a missed lease), deregisters on
``close()``, and owns an inbox: ACL messages in FIPA string form as
``std_msgs/String`` on ``/cf/agents/<name>/inbox``. It runs the cf_lang
conversation protocols on real messages (futures resolve on the final
answer or on the reply-by timeout), keeps a lookup cache fed by the ComMAg's
latched registry snapshot, and picks the best live provider for each request,
so a withdrawn or suspect provider is replaced by its redundant twin.

Inboxes use reliable, KEEP_ALL QoS: a fast sender is slowed down instead of
having messages dropped.

Several agents may share one process: give each the same :class:`~cf_commag.host.Host`. They
then share the ComMAg clients, the lookup cache, one timer and the outbox, and hand messages
to each other without DDS (host.py).
"""

from __future__ import annotations

import os
import time
import uuid
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from rclpy._rclpy_pybind11 import RCLError
from rclpy.node import Node
from rclpy.task import Future
from std_msgs.msg import String

from cf_interfaces.msg import ComponentRecord, KeyValue
from cf_interfaces.srv import Deregister, Lookup, Register
from cf_lang import LanguageError, acl, dumps, protocols
from cf_lang.acl import AclMessage, AgentId, Performative
from cf_lang.protocols import Conversation, ConversationTable
from cf_lang.taxonomy import Direction

from .guarded import GuardedNode, guard
from .host import Host
from .process import HOST_KEY, process_identity
from .records import Directory, Entry, Query, valid_agent_name
from .registry import INCARNATION_KEY, SUPERSEDED
from .transport.outbox import inbox_topic, sample_text
from .transport.qos import INBOX_QOS
from .transport.samples import sample_messages


def _parses(text: str) -> bool:
    try:
        acl.parse(text)
    except LanguageError:
        return False
    return True


class Refuse(Exception):
    """Raise from a handler to answer ``refuse`` with this reason."""


class Failure(Exception):
    """Raise from a handler to answer ``failure`` with this reason."""


@dataclass(frozen=True)
class Reply:
    """How a conversation ended: its final state and the last message (None on timeout)."""

    state: str
    message: AclMessage | None

    @property
    def ok(self) -> bool:
        return self.state == "done"

    @property
    def content(self) -> str | None:
        return self.message.content if self.message else None


class Responder:
    """The answering side of one conversation, handed to a handler."""

    def __init__(self, agent: Agent, conv: Conversation, request: AclMessage):
        self._agent = agent
        self.conversation = conv
        self.request = request
        self.on_cancel: Callable[[], None] | None = None

    @property
    def open(self) -> bool:
        return not self.conversation.finished and self.conversation.state != "cancelling"

    def _send(self, performative: Performative, content: str | None) -> None:
        msg = self.conversation.send(performative, content, now=time.monotonic())
        self._agent.send(msg)
        if self.conversation.finished:
            self._agent._responders.pop(self.conversation.conversation_id, None)

    def agree(self, content: str | None = None) -> None:
        self._send(Performative.AGREE, content)

    def inform(self, content: str | None = None) -> None:
        self._send(Performative.INFORM, content)

    def refuse(self, reason: str) -> None:
        self._send(Performative.REFUSE, _reason(self.request, reason))

    def failure(self, reason: str) -> None:
        self._send(Performative.FAILURE, _reason(self.request, reason))

    def not_understood(self, reason: str) -> None:
        self._send(Performative.NOT_UNDERSTOOD, _reason(self.request, reason))


def _reason(request: AclMessage, reason: str) -> str:
    """Content of refuse/failure, as FIPA has it: the action refused and why, ``("<content>" "<reason>")``."""
    return dumps([request.content or "", reason])


Handler = Callable[[AclMessage, Responder], str | None]


class Agent:
    """Registration, inbox, conversations and lookups for one component."""

    def __init__(
        self,
        node: Node,
        *,
        name: str,
        service_class: str,
        launch_command: Iterable[str] = (),
        team: str = "",
        player_number: int = 0,
        lease: float = 1.0,
        commag: str = "/commag",
        address: str = "",
        port: int = 0,
        transport: str = "ros",
        metadata: dict[str, str] | None = None,
        register: bool = True,
        on_message: Callable[[AclMessage], None] | None = None,
        host: Host | None = None,
    ):
        if not valid_agent_name(name):
            raise ValueError(f"agent name {name!r} must match [A-Za-z][A-Za-z0-9_]*")
        if host is not None and host.commag != commag:
            raise ValueError(f"{name}: the host talks to {host.commag}, not {commag}")
        self.node = node
        self.me = AgentId(name)
        identity = process_identity()
        if host is not None and host.name:
            identity[HOST_KEY] = host.name
        self.record = ComponentRecord(
            name=name,
            address=address,
            port=port,
            service_class=service_class,
            launch_command=list(launch_command),
            lease_period=float(lease),
            team=team,
            player_number=player_number,
            transport=transport,
            languages=["cf-lang"],
            ontologies=["robocup-soccer"],
            metadata=[
                KeyValue(key=k, value=v)
                for k, v in {
                    **(metadata or {}),
                    **identity,
                    INCARNATION_KEY: f"{os.getpid()}-{uuid.uuid4().hex[:12]}",
                }.items()
            ],
        )
        self.registered = False
        self.last_register_reason = ""
        self.on_message = on_message
        self.counters = {"received": 0, "sent": 0, "bad": 0}
        self._log = node.get_logger()
        self._table = ConversationTable()
        self._futures: dict[str, tuple[Future, Callable | None]] = {}
        self._responders: dict[str, Responder] = {}
        self._handlers: dict[str, Handler] = {}
        self._register = register
        self._closed = False
        # A standalone agent is the only one of its private host: the same code as a hosted one.
        self.host = host if host is not None else Host(node, commag=commag)
        self._renewer = self.host.renewer
        self._outbox = self.host.outbox
        self.host.add(self)

        def guarded(callback):  # a GuardedNode guards what it creates; a plain node does not
            return callback if isinstance(node, GuardedNode) else guard(callback, self._log, callback.__qualname__)

        # Taken serialized (see string_cdr): no message object built per sample.
        self._inbox = node.create_subscription(String, inbox_topic(name), guarded(self._on_inbox), INBOX_QOS, raw=True)

    @property
    def _directory(self) -> Directory:
        return self.host.directory

    def on_tick(self, now: float) -> None:
        """The host's timer (every 0.1 s): renew when due, expire conversations past their reply-by."""
        if self._closed:
            return
        if self._register:
            self._renew(now)
        if self._table:
            self._expire(now)

    # ---- registration ------------------------------------------------------

    def _renew(self, now: float) -> None:
        # Three renewals per lease (one late or lost renewal is not a missed lease); until the
        # first is answered, one per tick (discovery takes a moment).
        name = self.me.name
        if self._renewer.due(name, self.record.lease_period, now):
            request = Register.Request(component=self.record)
            self._renewer.send(name, request, now, guard(self._on_registered, self._log, "registration"))

    def _on_registered(self, future: Future) -> None:
        if future.cancelled() or future.exception() is not None:
            return
        response = future.result()
        if not response.accepted and response.reason == SUPERSEDED:
            # A newer process of this component took over: two must never serve under one name.
            # The whole process stops (its other agents were relaunched with it, and must not
            # deregister the new ones on the way out).
            self._log.error("a newer process of this component has registered; this one stops")
            for agent in list(self.host.agents.values()):
                agent._closed = True
            self.node.context.try_shutdown()
            return
        if not response.accepted:
            self._log.error(f"registration refused: {response.reason}", throttle_duration_sec=5.0)
        self.registered = response.accepted
        self.last_register_reason = response.reason

    def close(self) -> Future | None:
        """Stop renewing and deregister (so the ComMAg does not relaunch us).

        Returns a future that is done once the ComMAg answered (spin until it
        is done to be sure), or None if there was nothing to deregister. A
        renewal still in flight is answered first, so it cannot re-register
        us after the deregistration. Call :meth:`flush` afterwards to deliver
        what is still queued (deregistering first: a slow flush must not cost
        the lease and get a process that is exiting relaunched).
        """
        if self._closed:
            return None
        self._closed = True
        self.host.remove(self)
        done = Future()
        client = self.host.deregister_client
        try:
            if not self._register or not client.service_is_ready():
                return None
        except RCLError:  # the context is already shut down: nothing more we can say
            return None

        def deregister(_=None):
            try:
                answer = client.call_async(Deregister.Request(name=self.me.name))
                answer.add_done_callback(lambda f: done.set_result(True))
            except RCLError:
                done.set_result(False)

        pending = self._renewer.pending(self.me.name)
        if pending is not None:
            pending.add_done_callback(deregister)
        else:
            deregister()
        self.registered = False
        return done

    # ---- lookups -----------------------------------------------------------

    def providers(
        self,
        service_class: str,
        *,
        direction: Direction = Direction.GENERAL,
        team: str = "",
        player_number: int = 0,
        include_suspect: bool = False,
        exclude: Iterable[str] = (),
    ) -> list[Entry]:
        """Providers from the local cache, best first (healthy, nearest class)."""
        query = Query(service_class, direction, team, player_number, include_suspect)
        skip = set(exclude)
        return [e for e, _ in self._directory.search(query) if e.name not in skip]

    def provider(self, service_class: str, **filters) -> str | None:
        """The best live provider's name, or None. Call it per request: that is the failover."""
        found = self.providers(service_class, **filters)
        return found[0].name if found else None

    def lookup(self, service_class: str, **fields) -> Future:
        """Ask the ComMAg itself (authoritative); the future gives a Lookup.Response."""
        request = Lookup.Request(service_class=service_class, **fields)
        return self.host.lookup_client.call_async(request)

    # ---- sending -----------------------------------------------------------

    def send(self, msg: AclMessage) -> None:
        """Deliver a message to each receiver: in this process directly, elsewhere through its inbox."""
        if msg.sender is None:
            msg = msg._replace(sender=self.me)
        text = None
        host = self.host
        for receiver in msg.receivers:
            local = host.local(receiver.name)
            if local is not None:
                host.post(local, msg)
            elif valid_agent_name(receiver.name):
                if text is None:
                    text = acl.to_text(msg)
                self._outbox.send(receiver.name, text)
            else:
                self._log.warning(f"cannot send to {receiver.name!r}: not an agent name")
                continue
            self.counters["sent"] += 1

    def flush(self, timeout: float = 5.0) -> bool:
        """Wait until every receiver acknowledged every message sent so far.

        Call it before exiting: messages still queued in a publisher die with
        the process. Returns False if the timeout passed first.
        """
        deadline = time.monotonic() + timeout
        while self._outbox.held and time.monotonic() < deadline:
            time.sleep(0.01)
            self._outbox.flush()
        return self._outbox.held == 0 and self._outbox.wait_acked(max(0.0, deadline - time.monotonic()))

    def request(
        self,
        receiver: str,
        content: str,
        *,
        protocol: str = "fipa-request",
        timeout: float | None = 1.0,
        on_update: Callable[[AclMessage], None] | None = None,
    ) -> Future:
        """Start a conversation; the future resolves to a :class:`Reply`.

        ``on_update`` sees intermediate messages (agree, and each inform of a
        subscription). For ``fipa-subscribe`` the future resolves when the
        subscription ends; use :meth:`cancel` to end it.
        """
        if not valid_agent_name(receiver):
            raise ValueError(f"not an agent name: {receiver!r} (did a lookup find no provider?)")
        conv, first = protocols.initiate(
            protocol,
            me=self.me,
            peer=AgentId(receiver),
            content=content,
            now=time.monotonic(),
            wall=time.time(),
            timeout=timeout,
        )
        future = Future()
        self._table.add(conv)
        self._futures[conv.conversation_id] = (future, on_update)
        future.conversation_id = conv.conversation_id
        self.send(first)
        return future

    def cancel(self, future: Future) -> None:
        """Cancel a subscription started with :meth:`request`."""
        conv = self._table.get(getattr(future, "conversation_id", ""))
        if conv is not None and conv.state in ("subscribing", "subscribed"):
            self.send(conv.send(Performative.CANCEL, None, now=time.monotonic()))

    # ---- receiving ---------------------------------------------------------

    def serve(self, protocol: str, handler: Handler) -> None:
        """Answer conversations of ``protocol`` that others open with us.

        The handler gets the opening message and a :class:`Responder`. It may
        answer through the responder (now or later), or return a content string
        (sent as inform), or raise Refuse/Failure; a LanguageError (content
        that does not parse or validate) is answered not-understood.
        """
        if protocol not in protocols.PROTOCOLS:
            raise ValueError(f"unknown protocol {protocol!r}")
        self._handlers[protocol] = handler

    def _on_inbox(self, sample: bytes) -> None:
        data = sample_text(sample)
        if "\n" not in data:  # one message, the common case
            self._on_text(data)
            return
        texts = sample_messages(data)
        if len(texts) == 1:
            self._on_text(texts[0])
            return
        messages = []
        for text in texts:
            try:
                messages.append(acl.parse(text))
            except LanguageError:
                messages.append(text)
        if all(type(m) is str for m in messages) and _parses(data):
            # Not a batch but one message written over several lines (by a foreign sender).
            self._on_text(data)
            return
        with self._outbox.batch():  # what the handlers answer goes out as one sample per receiver
            for message in messages:
                self._on_text(message)

    def receive(self, message: AclMessage) -> None:
        """A message from an agent of the same process (see host.py)."""
        if not self._closed:
            self._on_text(message)

    def _on_text(self, text: str | AclMessage) -> None:
        self.counters["received"] += 1
        try:
            message = text if type(text) is AclMessage else acl.parse(text)
        except LanguageError as exc:
            self.counters["bad"] += 1
            self._log.warning(f"unreadable message: {exc}", throttle_duration_sec=2.0)
            return
        try:
            self._dispatch(message)
        except Exception as exc:  # a bad message must never stop the agent
            self.counters["bad"] += 1
            self._log.error(f"while handling a message: {exc!r}", throttle_duration_sec=2.0)

    def _dispatch(self, message: AclMessage) -> None:
        now = time.monotonic()
        cid = message.conversation_id or ""
        if cid in self._table:
            try:
                conv = self._table.dispatch(message, now=now)
            except LanguageError as exc:
                self.send(protocols.not_understood(message, str(exc), me=self.me))
                return
            future, on_update = self._futures.get(cid, (None, None))
            if conv.finished:
                self._futures.pop(cid, None)
                if future is not None and not future.done():
                    future.set_result(Reply(conv.state, message))
            elif on_update is not None:
                on_update(message)
            return
        responder = self._responders.get(cid)
        if responder is not None:
            try:
                responder.conversation.receive(message, now=now)
            except LanguageError as exc:
                self.send(protocols.not_understood(message, str(exc), me=self.me))
                return
            if responder.conversation.state == "cancelling":
                if responder.on_cancel is not None:
                    responder.on_cancel()
                responder.inform(None)
            return
        if message.performative in (
            Performative.REQUEST,
            Performative.QUERY_REF,
            Performative.QUERY_IF,
            Performative.SUBSCRIBE,
        ):
            self._open(message, now)
            return
        if message.performative is Performative.NOT_UNDERSTOOD:
            return  # never answer not-understood with not-understood
        if self.on_message is not None:
            self.on_message(message)
            return
        self.send(protocols.not_understood(message, "no open conversation for this message", me=self.me))

    def _open(self, message: AclMessage, now: float) -> None:
        try:
            acl.check_content(message)
            conv = protocols.respond(message, me=self.me, now=now)
        except LanguageError as exc:
            self.send(protocols.not_understood(message, str(exc), me=self.me))
            return
        handler = self._handlers.get(conv.spec.name)
        responder = Responder(self, conv, message)
        if handler is None:
            responder.refuse(f"{self.me.name} does not serve {conv.spec.name}")
            return
        self._responders[conv.conversation_id] = responder
        try:
            result = handler(message, responder)
        except Refuse as exc:
            if responder.open:
                responder.refuse(str(exc))
            return
        except LanguageError as exc:  # the content does not parse or names nothing we know
            if responder.open:
                responder.not_understood(str(exc))
            return
        except Failure as exc:
            if responder.open:
                responder.failure(str(exc))
            return
        except Exception as exc:
            if responder.open:
                responder.failure(f"internal error: {exc!r}")
            raise
        if result is not None and responder.open:
            responder.inform(result)

    def _expire(self, now: float) -> None:
        for conv in self._table.expire(now):
            future, _ = self._futures.pop(conv.conversation_id, (None, None))
            if future is not None and not future.done():
                future.set_result(Reply("timed-out", None))
