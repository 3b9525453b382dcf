"""The TCP socket gateway, ROS-free: wire protocol, sessions, limits, asyncio server.

Agents in any language connect over TCP and speak one S-expression per line
(UTF-8); docs/gateway-protocol.md is the specification. This module knows
nothing of ROS: everything the gateway does in the framework (register with
the ComMAg, look up, publish to inboxes, receive) goes through a :class:`Bus`
that the ROS node implements, and that tests replace with a fake.
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Protocol

from cf_lang import LanguageError, acl, dumps
from cf_lang.acl import AgentId
from cf_lang.sexp import Keyword, Limits, Symbol, loads
from cf_lang.taxonomy import Direction

from .records import Entry, Query, Record, Transport, valid_agent_name
from .registry import Result

PROTOCOL_VERSION = 1
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
    def open_inbox(self, name: str, deliver: Callable[[str], None]) -> None: ...
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


class Session:
    """One TCP agent: its protocol state and what it holds in the framework."""

    def __init__(self, gateway: Gateway, peer: tuple[str, int], send: Callable[[str], bool]):
        self.gateway = gateway
        self.peer = peer
        self.send = send
        self.name: str | None = None
        self.registered: Record | None = None
        self.last_seen = time.monotonic()
        self.closed = False

    # ---- lines in -----------------------------------------------------------

    async def handle(self, line: bytes) -> bool:
        """Handle one line; return False when the session should end."""
        self.last_seen = time.monotonic()
        line = line.rstrip(b"\r\n")
        if not line.strip():
            return True
        try:
            sexp = loads(line, limits=self.gateway.limits)
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
            self._send_acl(sexp)
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
        return await handler(self, params)

    async def _hello(self, params: dict) -> bool:
        if self.name is not None:
            self.send(form("failure", in_reply_to="hello", reason=f"already connected as {self.name}"))
            return True
        token = str(params.get("token", ""))
        if self.gateway.config.token and not hmac.compare_digest(token, self.gateway.config.token):
            self.send(form("failure", in_reply_to="hello", reason="wrong token"))
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
        self.gateway.bus.open_inbox(name, self.send)
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
            lease = float(params.get("lease", self.gateway.config.default_lease))
            record = Record(
                name=self.name,
                service_class=str(params.get("service-class", "")),
                address=str(params.get("address", self.peer[0])),
                port=int(params.get("port", self.peer[1])),
                lease_period=lease,
                team=str(params.get("team", "")),
                player_number=int(params.get("player", 0)),
                transport=Transport.TCP,
                languages=("cf-lang",),
                ontologies=("robocup-soccer",),
            )
        except (TypeError, ValueError) as exc:
            self.send(form("failure", in_reply_to="register", reason=f"bad parameter: {exc}"))
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
            direction = _DIRECTIONS[str(params.get("direction", "general")).lower()]
            query = Query(
                service_class=str(params.get("service-class", "")),
                direction=direction,
                team=str(params.get("team", "")),
                player_number=int(params.get("player", 0)),
                include_suspect=str(params.get("include-suspect", "false")).lower() == "true",
                max_results=int(params.get("max", 0)),
            )
            entries = await self.gateway.bus.lookup(query)
        except KeyError:
            self.send(
                form("failure", in_reply_to="lookup", reason=f"direction must be one of {', '.join(_DIRECTIONS)}")
            )
            return True
        except (LanguageError, TypeError, ValueError) as exc:
            self.send(form("failure", in_reply_to="lookup", reason=str(exc)))
            return True
        self.send(dumps([Symbol("providers"), *[entry_form(e) for e in entries]]))
        return True

    async def _ping(self, params: dict) -> bool:
        self.send(form("pong"))
        return True

    async def _events(self, params: dict) -> bool:
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

    _COMMANDS: dict[str, Callable[[Session, dict], Awaitable[bool]]] = {
        "hello": _hello,
        "register": _register,
        "lookup": _lookup,
        "ping": _ping,
        "events": _events,
        "bye": _bye,
    }

    def _send_acl(self, sexp: list) -> None:
        try:
            msg = acl.from_sexp(sexp)
        except LanguageError as exc:
            self.send(form("not-understood", reason=str(exc)))
            return
        perf = msg.performative.value
        if msg.sender is not None and msg.sender.name != self.name:
            self.send(form("failure", in_reply_to=perf, reason=f"you are {self.name}, not {msg.sender.name}"))
            return
        if not msg.receivers:
            self.send(form("failure", in_reply_to=perf, reason="no :receiver"))
            return
        unknown = [r.name for r in msg.receivers if not self.gateway.bus.known(r.name)]
        if unknown:
            self.send(form("failure", in_reply_to=perf, reason=f"unknown receiver {', '.join(unknown)}"))
            return
        if msg.sender is None:
            # Say who sent it; the rest of the line goes on as the agent wrote it.
            sexp = [sexp[0], _K_SENDER, AgentId(self.name).to_sexp(), *sexp[1:]]
        text = dumps(sexp)
        for receiver in msg.receivers:
            self.gateway.bus.publish(receiver.name, text)
        self.gateway.relayed += 1

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
        self.sessions: dict[str, Session] = {}
        self.connections = 0
        self.relayed = 0
        self.slow_disconnects = 0
        self.port: int | None = None
        self._server: asyncio.base_events.Server | None = None

    async def start(self) -> int:
        """Listen; return the bound port (useful with port 0)."""
        self._server = await asyncio.start_server(
            self._serve, self.config.host, self.config.port, limit=self.config.max_line_bytes + 1
        )
        self.port = self._server.sockets[0].getsockname()[1]
        return self.port

    async def stop(self) -> None:
        if self._server is not None:
            self._server.close()
            for session in list(self.sessions.values()):
                session.release()
            await self._server.wait_closed()

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

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        peer = writer.get_extra_info("peername")[:2]
        if self.connections >= self.config.max_connections:
            writer.write((form("error", reason="too many connections") + "\n").encode())
            await _close(writer)
            return
        self.connections += 1
        queue: asyncio.Queue[str | None] = asyncio.Queue()
        state = {"dropped": False}

        def send(text: str) -> bool:
            # Called from the loop thread only. A reader that falls behind by more than
            # max_queue lines or max_pending_bytes unsent is disconnected, instead of
            # slowing everyone down or losing messages silently.
            if state["dropped"]:
                return False
            if queue.qsize() >= self.config.max_queue or (
                writer.transport.get_write_buffer_size() > self.config.max_pending_bytes
            ):
                state["dropped"] = True
                self.slow_disconnects += 1
                queue.put_nowait(None)
                # Give the writer a moment to say why, then cut the connection for good.
                asyncio.get_running_loop().call_later(1.0, writer.transport.abort)
                return False
            queue.put_nowait(text)
            return True

        session = Session(self, peer, send)
        writer_task = asyncio.create_task(self._write(writer, queue, state))
        try:
            await self._read(reader, session, state)
        except FramingError as exc:
            send(form("error", reason=str(exc)))
        except (ConnectionError, asyncio.IncompleteReadError):
            pass
        except Exception as exc:  # a bug must cost one connection, never the gateway
            self.log(f"session {session.name or peer}: {exc!r}")
            send(form("error", reason=f"internal error: {exc!r}"))
        finally:
            session.release()
            self.connections -= 1
            queue.put_nowait(None)
            try:
                await asyncio.wait_for(writer_task, 2.0)
            except TimeoutError:
                writer.transport.abort()
            await _close(writer)

    async def _read(self, reader: asyncio.StreamReader, session: Session, state: dict) -> None:
        timeout = self.config.hello_timeout
        while not state["dropped"]:
            try:
                if session.name is None:
                    line = await asyncio.wait_for(reader.readuntil(b"\n"), timeout)
                else:
                    line = await reader.readuntil(b"\n")
            except TimeoutError:
                raise FramingError(f"no hello within {timeout} s") from None
            except asyncio.LimitOverrunError:
                raise FramingError(f"line longer than {self.config.max_line_bytes} bytes") from None
            except asyncio.IncompleteReadError as exc:
                if exc.partial.strip():
                    raise FramingError("connection closed in the middle of a line") from None
                return
            if not await session.handle(line):
                return

    async def _write(self, writer: asyncio.StreamWriter, queue: asyncio.Queue, state: dict) -> None:
        try:
            while True:
                batch = [await queue.get()]
                while not queue.empty() and len(batch) < 256:  # one write call for what is waiting
                    batch.append(queue.get_nowait())
                end = batch.index(None) if None in batch else len(batch)
                if end:
                    writer.write("\n".join(batch[:end]).encode() + b"\n")
                if end < len(batch):
                    if state["dropped"]:
                        writer.write(
                            (form("error", reason="too slow: outbound queue full, disconnecting") + "\n").encode()
                        )
                    return
                if writer.transport.get_write_buffer_size() > self.config.max_pending_bytes // 4:
                    await writer.drain()
        except (ConnectionError, RuntimeError):
            state["dropped"] = True


async def _close(writer: asyncio.StreamWriter) -> None:
    with contextlib.suppress(ConnectionError, TimeoutError, RuntimeError):
        await asyncio.wait_for(writer.drain(), 1.0)
    writer.close()
    with contextlib.suppress(ConnectionError, TimeoutError, RuntimeError):
        await asyncio.wait_for(writer.wait_closed(), 1.0)
