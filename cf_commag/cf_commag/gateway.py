"""The TCP socket gateway, ROS-free: wire protocol, sessions, limits, asyncio server.

Agents in any language connect over TCP and speak one S-expression per line
(UTF-8); docs/gateway-protocol.md is the specification. This module knows
nothing of ROS: everything the gateway does in the framework (register with
the ComMAg, look up, publish to inboxes, receive) goes through a :class:`Bus`
that the ROS node implements, and that tests replace with a fake.
"""

from __future__ import annotations

import asyncio
import hmac
import math
import socket
import threading
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Protocol

from cf_lang import LanguageError, acl, acl_fast, dumps
from cf_lang.acl import AgentId
from cf_lang.sexp import Keyword, Limits, Symbol, loads
from cf_lang.taxonomy import Direction

from .records import Entry, Query, Record, Transport, query_field_problem, record_field_problem, valid_agent_name
from .registry import Result
from .transport.samples import pack_lines

PROTOCOL_VERSION = 1
LOOKUP_TRUST = 10.0  # s a lookup answer's names count as known, whatever the registry snapshot says
LOOKUP_MEMORY = 10_000  # names remembered from lookup answers before the stale ones are forgotten
_K_SENDER = Keyword("sender")
_DIRECTIONS = {d.name.lower(): d for d in Direction}
_PERFORMATIVES = {p.value for p in acl.Performative}


class Bus(Protocol):
    """What the gateway needs from the framework (the ROS node provides it)."""

    def register(self, record: Record) -> Awaitable[Result]: ...
    def deregister(self, name: str) -> Awaitable[Result]: ...
    def lookup(self, query: Query) -> Awaitable[list[Entry]]: ...
    def known(self, name: str) -> bool: ...
    def publish(self, receiver: str, text: str) -> None: ...
    def open_inbox(self, name: str, deliver: Callable[[str], bool]) -> None:
        """Start delivering ``name``'s inbox samples; ``deliver`` may be called from any thread."""

    def close_inbox(self, name: str) -> None: ...
    def watch_events(self, key: object, deliver: Callable[[str], None] | None) -> None: ...


@dataclass(frozen=True)
class GatewayConfig:
    host: str = "127.0.0.1"
    port: int = 7700
    token: str = ""
    max_connections: int = 256
    max_line_bytes: int = 65_536
    max_depth: int = 32
    max_queue: int = 10_000
    max_pending_bytes: int = 4 << 20
    default_lease: float = 2.0
    hello_timeout: float = 10.0


class FramingError(Exception):
    """The byte stream cannot be split into lines any more: the connection closes."""


def form(head: str, **params) -> str:
    """A gateway line: ``(head :key value ...)``."""
    items: list = [Symbol(head)]
    for key, value in params.items():
        if value is None:
            continue
        items.append(Keyword(key.replace("_", "-")))
        items.append(value)
    return dumps(items)


def _pairs(items: list) -> dict[str, object]:
    if len(items) % 2:
        raise ValueError("expected :key value pairs")
    out = {}
    for i in range(0, len(items), 2):
        if type(items[i]) is not Keyword:
            raise ValueError(f"expected a :key, found {dumps(items[i])}")
        out[items[i].name] = items[i + 1]
    return out


def _param(params: dict, key: str, kind: type, default):
    """Parameter ``:key`` read as ``kind`` (str, int, float or bool); ValueError saying why not."""
    if key not in params:
        return default
    value = params[key]
    if kind is str and isinstance(value, str):
        return str(value)
    if kind is bool and isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    if kind is int and type(value) is int:
        return value
    if kind is float and type(value) in (int, float):
        try:
            number = float(value)
        except OverflowError:  # an integer of hundreds of digits
            number = math.inf
        if math.isfinite(number):
            return number
    wanted = {str: "a string", int: "an integer", float: "a finite number", bool: "true or false"}[kind]
    raise ValueError(f"bad parameter :{key}: expected {wanted}, found {dumps(value)[:40]}")


def entry_form(entry: Entry) -> list:
    rec = entry.record
    return [
        Symbol("provider"),
        Keyword("name"),
        rec.name,
        Keyword("service-class"),
        rec.service_class,
        Keyword("state"),
        entry.state.value,
        Keyword("team"),
        rec.team,
        Keyword("player"),
        rec.player_number,
        Keyword("transport"),
        rec.transport.value,
        Keyword("address"),
        rec.address,
        Keyword("port"),
        rec.port,
    ]


class TcpAgent:
    """One TCP agent: its protocol state and what it holds in the framework."""

    def __init__(
        self,
        gateway: Gateway,
        peer: tuple[str, int],
        send: Callable[[str], bool],
        deliver: Callable[[str], bool] | None = None,
    ):
        self.gateway = gateway
        self.peer = peer
        self.send = send  # the gateway's own answers (loop thread)
        self.deliver = deliver or send  # messages from the inbox (any thread)
        self.name: str | None = None
        self.registered: Record | None = None
        self.last_seen = time.monotonic()
        self.closed = False

    # ---- lines in -----------------------------------------------------------

    def handle(self, line: bytes) -> bool | Awaitable[bool]:
        """Handle one line: True to go on, False to end the session, or an awaitable
        giving one of those for commands that wait for the ComMAg (the lines after
        it wait too, so an agent's lines take effect in order)."""
        self.last_seen = time.monotonic()
        line = line.rstrip(b"\r\n")
        if not line.strip():
            return True
        try:
            text = line.decode()
        except UnicodeDecodeError:
            text = None  # the reader says where and why
        if text is not None and self.name is not None:
            found = acl_fast.split(text, self.gateway.limits)
            if found is not None and found[0].lower() in _PERFORMATIVES:  # the common shape, one regex run
                self._send_fast(*found, text)
                return True
        try:
            sexp = loads(line if text is None else text, limits=self.gateway.limits)
        except LanguageError as exc:
            self.send(form("not-understood", reason=str(exc)))
            return True
        if type(sexp) is not list or not sexp or type(sexp[0]) is not Symbol:
            self.send(form("not-understood", reason=f"expected (command ...), found {dumps(sexp)[:60]}"))
            return True
        head = str(sexp[0]).lower()
        if self.name is None and head != "hello":
            self.send(form("failure", in_reply_to=head, reason="say (hello :name ...) first"))
            return True
        if head in _PERFORMATIVES:
            self._send_acl(sexp, text)
            return True
        handler = self._COMMANDS.get(head)
        if handler is None:
            known = ", ".join(self._COMMANDS)
            self.send(form("not-understood", reason=f"unknown command {head}; commands: {known}; or an ACL message"))
            return True
        try:
            params = _pairs(sexp[1:])
        except ValueError as exc:
            self.send(form("failure", in_reply_to=head, reason=str(exc)))
            return True
        return handler(self, params)

    def _hello(self, params: dict) -> bool:
        if self.name is not None:
            self.send(form("failure", in_reply_to="hello", reason=f"already connected as {self.name}"))
            return True
        token = str(params.get("token", ""))
        if self.gateway.config.token and not hmac.compare_digest(token, self.gateway.config.token):
            self.send(form("failure", in_reply_to="hello", reason="wrong token"))
            self.send(form("error", reason="wrong token"))  # every close the gateway makes ends with error
            return False
        name = str(params.get("name", ""))
        if not valid_agent_name(name):
            self.send(form("failure", in_reply_to="hello", reason=f"name {name!r} must match [A-Za-z][A-Za-z0-9_]*"))
            return True
        if name in self.gateway.sessions:
            self.send(form("failure", in_reply_to="hello", reason=f"{name} is already connected"))
            return True
        self.name = name
        self.gateway.sessions[name] = self
        self.gateway.bus.open_inbox(name, self.deliver)
        self.send(
            form(
                "welcome",
                name=name,
                version=PROTOCOL_VERSION,
                max_line=self.gateway.config.max_line_bytes,
                max_depth=self.gateway.config.max_depth,
            )
        )
        return True

    async def _register(self, params: dict) -> bool:
        if "launch-command" in params:
            self.send(form("failure", in_reply_to="register", reason="TCP agents cannot register a launch command"))
            return True
        try:
            record = Record(
                name=self.name,
                service_class=_param(params, "service-class", str, ""),
                address=_param(params, "address", str, self.peer[0]),
                port=_param(params, "port", int, self.peer[1]),
                lease_period=_param(params, "lease", float, self.gateway.config.default_lease),
                team=_param(params, "team", str, ""),
                player_number=_param(params, "player", int, 0),
                transport=Transport.TCP,
                languages=("cf-lang",),
                ontologies=("robocup-soccer",),
            )
        except ValueError as exc:
            self.send(form("failure", in_reply_to="register", reason=str(exc)))
            return True
        problem = record_field_problem(record)  # what a ROS message could not carry
        if problem:
            self.send(form("failure", in_reply_to="register", reason=f"bad parameter: {problem}"))
            return True
        result = await self.gateway.bus.register(record)
        if not result.accepted:
            self.send(form("failure", in_reply_to="register", reason=result.reason))
            return True
        self.registered = record
        self.send(form("registered", name=self.name, lease=result.lease))
        return True

    async def _lookup(self, params: dict) -> bool:
        try:
            direction = _param(params, "direction", str, "general").lower()
            if direction not in _DIRECTIONS:
                raise ValueError(f"bad parameter: direction must be one of {', '.join(_DIRECTIONS)}")
            query = Query(
                service_class=_param(params, "service-class", str, ""),
                direction=_DIRECTIONS[direction],
                team=_param(params, "team", str, ""),
                player_number=_param(params, "player", int, 0),
                include_suspect=_param(params, "include-suspect", bool, False),
                max_results=_param(params, "max", int, 0),
            )
            problem = query_field_problem(query)
            if problem:
                raise ValueError(f"bad parameter: {problem}")
            entries = await self.gateway.bus.lookup(query)
        except (LanguageError, ValueError) as exc:
            self.send(form("failure", in_reply_to="lookup", reason=str(exc)))
            return True
        self.gateway.looked_up(e.record.name for e in entries)
        self.send(dumps([Symbol("providers"), *[entry_form(e) for e in entries]]))
        return True

    def _ping(self, params: dict) -> bool:
        self.send(form("pong"))
        return True

    def _events(self, params: dict) -> bool:
        on = str(params.get("on", "true")).lower() != "false"
        self.gateway.bus.watch_events(self, self.send if on else None)
        self.send(form("events", on=Symbol("true" if on else "false")))
        return True

    async def _bye(self, params: dict) -> bool:
        if self.registered is not None:
            await self.gateway.bus.deregister(self.name)
            self.registered = None
        self.send(form("bye"))
        return False

    _COMMANDS: dict[str, Callable[[TcpAgent, dict], bool | Awaitable[bool]]] = {
        "hello": _hello,
        "register": _register,
        "lookup": _lookup,
        "ping": _ping,
        "events": _events,
        "bye": _bye,
    }

    def _send_fast(self, written: str, end: int, pairs: list[tuple[str, str]], text: str) -> None:
        """An ACL line the fast reader split (cf_lang.acl_fast): only the reply-by date is left to check."""
        sender = receivers = None
        for key, value in pairs:
            if key == "receiver":
                receivers = acl_fast.names(value)
            elif key == "sender":
                sender = acl_fast.names(value)[0]
            elif key == "reply-by":
                try:
                    acl.parse_datetime(value)
                except LanguageError as exc:
                    self.send(form("not-understood", reason=str(exc)))
                    return
        self._relay_acl(written.lower(), sender, receivers or [], text[end:], None)

    def _send_acl(self, sexp: list, text: str) -> None:
        try:
            msg = acl.from_sexp(sexp)
        except LanguageError as exc:
            self.send(form("not-understood", reason=str(exc)))
            return
        written = sexp[0]
        body = text.strip()[1:].lstrip()
        rest = body[len(written) :] if body.startswith(written) else None
        sender = msg.sender.name if msg.sender is not None else None
        self._relay_acl(msg.performative.value, sender, [r.name for r in msg.receivers], rest, sexp)

    def _relay_acl(self, perf: str, sender: str | None, receivers: list[str], rest: str | None, sexp) -> None:
        """Check the sender and receivers, then relay the line: as written after the
        performative (``rest``) when there is that, else written again from ``sexp``."""
        if sender is not None and sender != self.name:
            self.send(form("failure", in_reply_to=perf, reason=f"you are {self.name}, not {sender}"))
            return
        if not receivers:
            self.send(form("failure", in_reply_to=perf, reason="no :receiver"))
            return
        known = self.gateway.known
        unknown = [r for r in receivers if not known(r)]
        if unknown:
            self.send(form("failure", in_reply_to=perf, reason=f"unknown receiver {', '.join(unknown)}"))
            return
        # The performative in lower case and a missing sender put in right after it.
        if rest is not None:
            text = f"({perf}{rest}" if sender else f"({perf} :sender (agent-identifier :name {self.name}){rest}"
        else:
            own = [] if sender else [_K_SENDER, AgentId(self.name).to_sexp()]
            text = dumps([Symbol(perf), *own, *sexp[1:]])
        relay = self.gateway.relay
        for receiver in receivers:
            relay(receiver, text)

    # ---- end ----------------------------------------------------------------

    def release(self) -> None:
        """Give back everything the session held. The ComMAg decides about the component:
        a registered agent that vanished stops being renewed and is withdrawn."""
        if self.closed:
            return
        self.closed = True
        if self.name is not None and self.gateway.sessions.get(self.name) is self:
            del self.gateway.sessions[self.name]
            self.gateway.bus.close_inbox(self.name)
        self.gateway.bus.watch_events(self, None)


class Gateway:
    """The asyncio TCP server and its sessions."""

    def __init__(self, config: GatewayConfig, bus: Bus, log: Callable[[str], None] = print):
        self.config = config
        self.bus = bus
        self.log = log
        self.limits = Limits(max_bytes=config.max_line_bytes, max_depth=config.max_depth)
        self.sessions: dict[str, TcpAgent] = {}
        self.connections = 0
        self.relayed = 0
        self.slow_disconnects = 0
        self.port: int | None = None
        self._server: asyncio.base_events.Server | None = None
        self._open: set[_Connection] = set()
        self._outgoing: dict[str, list[str]] = {}
        self._flush_due = False
        self._looked_up: dict[str, float] = {}  # name -> when a lookup answer named it (monotonic)

    def known(self, name: str) -> bool:
        """Whether ``name`` is an agent one may send to: in the ComMAg's last registry snapshot,
        or named by one of its lookup answers within LOOKUP_TRUST seconds.

        Snapshots reach the gateway a moment after the ComMAg answers, so an agent that
        registered just now may be missing from the last one; an agent that a lookup has
        just named must be reachable all the same (a C++ agent's request to the provider
        it had looked up was refused as to an unknown receiver, and it waited for ever).
        """
        if self.bus.known(name):
            return True
        seen = self._looked_up.get(name)
        return seen is not None and time.monotonic() - seen <= LOOKUP_TRUST

    def looked_up(self, names) -> None:
        """Note the names a lookup answer gave (see :meth:`known`)."""
        now = time.monotonic()
        if len(self._looked_up) > LOOKUP_MEMORY:  # forget the stale ones, so that lookups cannot grow it
            self._looked_up = {n: t for n, t in self._looked_up.items() if now - t <= LOOKUP_TRUST}
        for name in names:
            self._looked_up[name] = now

    async def start(self) -> int:
        """Listen; return the bound port (useful with port 0)."""
        loop = asyncio.get_running_loop()
        self._server = await loop.create_server(lambda: _Connection(self), self.config.host, self.config.port)
        self.port = self._server.sockets[0].getsockname()[1]
        return self.port

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
            for conn in list(self._open):
                conn.finish(abort=True)
            await self._server.wait_closed()

    def relay(self, receiver: str, text: str) -> None:
        """Queue an ACL message for a receiver's inbox; :meth:`after_read` publishes.

        Everything the connections brought in during one turn of the loop goes
        out as one sample per receiver: a DDS sample costs the same tens of
        microseconds whatever it holds, and 200 agents talking to one
        teammate then cost it a few samples instead of 200.
        """
        self._outgoing.setdefault(receiver, []).append(text)
        self.relayed += 1

    def after_read(self) -> None:
        """Publish what was relayed, now if nothing else waits in this loop turn, else after it."""
        if not self._outgoing or self._flush_due:
            return
        loop = asyncio.get_running_loop()
        # Other connections' reads of this turn wait in the loop's ready queue (an
        # attribute of CPython's loop, hence the care): publish after them, together.
        # With nothing waiting, publish at once: a turn of the loop costs latency.
        ready = getattr(loop, "_ready", None)
        if ready is None or len(ready) > 0:
            self._flush_due = True
            loop.call_soon(self.flush_relayed)
        else:
            self.flush_relayed()

    def flush_relayed(self) -> None:
        self._flush_due = False
        outgoing, self._outgoing = self._outgoing, {}
        publish = self.bus.publish
        for receiver, texts in outgoing.items():
            if len(texts) == 1:
                publish(receiver, texts[0])
            else:
                for chunk in pack_lines(texts):
                    publish(receiver, chunk)

    def due_renewals(self, now: float) -> list[Record]:
        """Records whose agents showed life within their lease: renew those, and only those.

        A hung or vanished agent stops being renewed, so the ComMAg sees it
        miss its lease exactly like any other component.
        """
        return [
            s.registered
            for s in self.sessions.values()
            if s.registered is not None and now - s.last_seen <= s.registered.lease_period
        ]


# Seconds a closing connection has to read its last lines: the abort after it throws away what is
# unsent (the final error too). At 1 s a client starved on a loaded machine lost its final line.
CLOSE_GRACE = 5.0


class _Connection(asyncio.Protocol):
    """One TCP connection: splits the byte stream into lines for its session and writes its answers.

    A low-level protocol rather than streams: one read brings many lines, which
    are handled in one go (and their ACL messages relayed together), and an
    answer is written straight to the transport without a writer task.
    """

    def __init__(self, gateway: Gateway):
        self.gateway = gateway
        self.config = gateway.config
        self.transport: asyncio.Transport | None = None
        self.session: TcpAgent | None = None
        self.buffer = bytearray()
        self.busy = False  # a command waits for the ComMAg; later lines wait for it
        self.eof = False
        self.closing = False  # nothing more is read or written
        self.finished = False
        self.counted = False
        self.backlog = 0  # lines written since the transport's buffer was last empty
        self.hello_timer: asyncio.TimerHandle | None = None
        self.command: asyncio.Future | None = None
        self.loop: asyncio.AbstractEventLoop | None = None
        self.direct: socket.socket | None = None
        self.lock = threading.Lock()  # one writer at a time: the loop thread or a delivering one
        self.deferred: list[bytes] = []  # bytes waiting for the loop thread, in order

    # ---- asyncio callbacks --------------------------------------------------

    def connection_made(self, transport: asyncio.Transport) -> None:
        self.transport = transport
        gateway = self.gateway
        gateway._open.add(self)
        if gateway.connections >= self.config.max_connections:
            transport.write((form("error", reason="too many connections") + "\n").encode())
            self.finish()
            return
        gateway.connections += 1
        self.counted = True
        peer = transport.get_extra_info("peername")[:2]
        self.session = TcpAgent(gateway, peer, self.send, self.deliver)
        self.loop = asyncio.get_running_loop()
        # A second handle on the socket, ours, so that inbox samples arriving on the ROS
        # executor's thread are written at once, without waking the loop (see deliver).
        self.direct = transport.get_extra_info("socket").dup()
        self.direct.setblocking(False)
        self.hello_timer = self.loop.call_later(self.config.hello_timeout, self._hello_overdue)

    def data_received(self, data: bytes) -> None:
        if self.closing:
            return  # after the last line: dropped (see finish)
        self.buffer += data
        if self.busy:
            if len(self.buffer) > 2 * self.config.max_line_bytes:
                self.transport.pause_reading()  # resumed when the command is answered
            return
        self._process()

    def eof_received(self) -> bool:
        if self.finished:
            return False  # the client has read our last line and closed: close
        self.eof = True
        if not self.busy:
            self._process()
        return True  # we close once the last answers are written

    def connection_lost(self, exc: Exception | None) -> None:
        self.closing = True
        with self.lock:
            if self.direct is not None:
                self.direct.close()
        self._release()
        self.gateway._open.discard(self)

    # ---- lines in -----------------------------------------------------------

    def _process(self) -> None:
        buffer = self.buffer
        limit = self.config.max_line_bytes
        start = 0
        try:
            while not self.busy and not self.closing:
                end = buffer.find(b"\n", start)
                if end < 0:
                    break
                if end - start > limit:
                    self._framing_error(f"line longer than {limit} bytes")
                    return
                line = bytes(buffer[start:end])
                start = end + 1
                result = self.session.handle(line)
                if result is False:
                    self.finish()
                elif result is not True:
                    self.busy = True
                    self.command = asyncio.ensure_future(self._wait_for(result))  # referenced: never collected
            del buffer[:start]
            if self.closing or self.busy:
                return
            if len(buffer) > limit:
                self._framing_error(f"line longer than {limit} bytes")
            elif self.eof:
                if buffer.strip():
                    self._framing_error("connection closed in the middle of a line")
                else:
                    self.finish()
        except Exception as exc:  # a bug must cost one connection, never the gateway
            name = self.session.name if self.session else None
            self.gateway.log(f"session {name or self.transport.get_extra_info('peername')}: {exc!r}")
            self.send(form("error", reason=f"internal error: {exc!r}"))
            self.finish()
        finally:
            self.gateway.after_read()

    async def _wait_for(self, answer: Awaitable[bool]) -> None:
        try:
            go_on = await answer
        except Exception as exc:
            self.gateway.log(f"session {self.session.name}: {exc!r}")
            self.send(form("error", reason=f"internal error: {exc!r}"))
            go_on = False
        self.busy = False
        if not go_on:
            self.finish()
            return
        if not self.closing:
            self.transport.resume_reading()
            self._process()

    def _hello_overdue(self) -> None:
        if self.session is not None and self.session.name is None and not self.closing:
            self.send(form("error", reason=f"no hello within {self.config.hello_timeout} s"))
            self.finish()

    def _framing_error(self, reason: str) -> None:
        self.send(form("error", reason=reason))
        self.finish()

    # ---- lines out ----------------------------------------------------------

    def send(self, text: str) -> bool:
        """Write one or more lines; on the loop thread (the gateway's own answers)."""
        with self.lock:
            if self.deferred:  # keep the byte order: after what waits already
                self.deferred.append(text.encode() + b"\n")
                return not self.closing
            return self._write(text.encode() + b"\n")

    def deliver(self, text: str) -> bool:
        """Write inbox messages (one or more lines); from any thread.

        The common case, nothing waiting to be written, sends straight on the
        socket from the calling thread: waking the loop thread for it costs more
        than the rest of the gateway's work on a message. A partial send, or
        anything already waiting, goes through the loop thread in order.
        """
        data = text.encode() + b"\n"
        with self.lock:
            if self.closing:
                return False
            if not self.deferred and self._nothing_buffered():
                try:
                    sent = self.direct.send(data)
                except (BlockingIOError, InterruptedError):
                    sent = 0
                except OSError:
                    return False  # the connection is gone; connection_lost releases it
                if sent == len(data):
                    self.backlog = 0
                    return True
                data = data[sent:]
            self.deferred.append(data)
            first = len(self.deferred) == 1
        if first:
            self.loop.call_soon_threadsafe(self._write_deferred)
        return True

    def _nothing_buffered(self) -> bool:
        try:
            return self.transport.get_write_buffer_size() == 0
        except RuntimeError:  # Python 3.12 sums a deque the loop thread may be changing
            return False

    def _write_deferred(self) -> None:
        with self.lock:
            data, self.deferred = b"".join(self.deferred), []
            if data:
                self._write(data)

    def _write(self, data: bytes) -> bool:
        """Write through the transport, holding the lock, on the loop thread.

        A reader that falls behind by more than max_queue lines or
        max_pending_bytes unsent is disconnected, instead of slowing everyone
        down or losing messages silently.
        """
        if self.closing:
            return False
        transport = self.transport
        pending = transport.get_write_buffer_size()
        if pending == 0:
            self.backlog = 0
        self.backlog += data.count(b"\n")
        if self.backlog > self.config.max_queue or pending + len(data) > self.config.max_pending_bytes:
            self.gateway.slow_disconnects += 1
            transport.write((form("error", reason="too slow: outbound queue full, disconnecting") + "\n").encode())
            self.loop.call_soon(self.finish)  # not under the lock
            self.closing = True
            return False
        transport.write(data)
        return True

    # ---- end ----------------------------------------------------------------

    def finish(self, abort: bool = False) -> None:
        """Release the session; close once what was written has gone (at most CLOSE_GRACE later)."""
        if self.finished and not abort:
            return
        with self.lock:
            # Lines a delivering thread left for the loop thread go out before the close:
            # a (bye) or final error handled before that write must not drop them.
            if self.deferred and not abort and not self.closing:
                data, self.deferred = b"".join(self.deferred), []
                self._write(data)
            self.finished = self.closing = True
        self._release()
        transport = self.transport
        if abort:
            transport.abort()
            return
        if self.eof:  # the client has closed its side already: nothing more will come
            transport.close()
        else:
            # Half-close, then read and drop what the client still sends until it closes too.
            # Closing a socket with unread input makes the kernel send a reset, and a reset
            # can destroy the final (error ...) line before the client has read it.
            transport.write_eof()
            transport.resume_reading()
        # A peer that never reads, or never closes, would keep the socket open for ever.
        asyncio.get_running_loop().call_later(CLOSE_GRACE, transport.abort)

    def _release(self) -> None:
        if self.hello_timer is not None:
            self.hello_timer.cancel()
            self.hello_timer = None
        if self.session is not None:
            self.session.release()
        if self.counted:
            self.counted = False
            self.gateway.connections -= 1
