"""A small Python client of the TCP gateway (no ROS needed): what a Python agent elsewhere uses.

    with GatewayClient("127.0.0.1", 7700, name="py_scout") as gw:
        gw.register("Perception", team="blue", player=9)
        provider = gw.lookup("Kick", team="blue")[0]["name"]
        reply = gw.request(provider, "(exec Player kick :playerNumber 9 :whichTeam our :power 60 :direction 0)")

Lines from the gateway are either gateway forms (welcome, registered,
providers, pong, event, failure/not-understood without a :sender, error,
bye) or ACL messages from other agents. Messages that arrive while the client
waits for something else are kept in ``inbox``.
"""

from __future__ import annotations

import contextlib
import itertools
import socket
import time
from collections import deque

from cf_lang import acl, dumps, loads
from cf_lang.acl import AclMessage, AgentId, Performative
from cf_lang.sexp import Keyword, Symbol


class GatewayError(Exception):
    """The gateway answered failure, not-understood or error."""


class GatewayClient:
    def __init__(self, host: str, port: int, *, name: str, token: str = "", timeout: float = 10.0):
        self.name = name
        self.timeout = timeout
        self.sock = socket.create_connection((host, port), timeout=timeout)
        self.file = self.sock.makefile("wb")
        self._buffer = bytearray()
        self.inbox: deque[AclMessage] = deque()
        self.events: deque[dict] = deque()
        self._ids = itertools.count(1)
        params = {"name": name, **({"token": token} if token else {})}
        self.welcome = self.command("hello", expect="welcome", **params)

    def __enter__(self) -> GatewayClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # ---- lines ----------------------------------------------------------------

    def send_line(self, line: str) -> None:
        self.file.write(line.encode("utf-8") + b"\n")
        self.file.flush()

    def read(self, deadline: float | None = None) -> list:
        """The next line, read; TimeoutError if none is complete by ``deadline`` (monotonic)."""
        return loads(self.read_line(deadline))

    def read_line(self, deadline: float | None = None) -> bytes:
        """The next line as it came, without its newline; TimeoutError as :meth:`read`.

        Lines are split here rather than by a socket file: a file cannot be read
        again once a read of it timed out, and a request's deadline must not end
        the connection.
        """
        while (end := self._buffer.find(b"\n")) < 0:
            if deadline is not None:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise TimeoutError("no line from the gateway in time")
                self.sock.settimeout(left)
            try:
                chunk = self.sock.recv(65536)
            finally:
                if deadline is not None:
                    self.sock.settimeout(self.timeout)
            if not chunk:
                raise ConnectionError("the gateway closed the connection")
            self._buffer += chunk
        line = bytes(self._buffer[:end])
        del self._buffer[: end + 1]
        return line

    def _next(self, expect: str) -> dict:
        """Read until a gateway form named ``expect``; file ACL messages and events on the way."""
        while True:
            sexp = self.read()
            head = str(sexp[0])
            params = _pairs(sexp[1:])
            _raise_if_refused(head, params)
            if head == expect:
                return {"_items": sexp[1:], **params}
            if head == "event":
                self.events.append(params)
            elif head in _PERFORMATIVES:
                self.inbox.append(acl.from_sexp(sexp))

    def command(self, head: str, *, expect: str, **params) -> dict:
        items: list = [Symbol(head)]
        for key, value in params.items():
            items += [Keyword(key.replace("_", "-")), value]
        self.send_line(dumps(items))
        return self._next(expect)

    # ---- the protocol ---------------------------------------------------------

    def register(self, service_class: str, *, team: str = "", player: int = 0, lease: float = 2.0) -> float:
        return self.command(
            "register", expect="registered", service_class=service_class, team=team, player=player, lease=lease
        )["lease"]

    def lookup(self, service_class: str, *, direction: str = "general", team: str = "", player: int = 0) -> list[dict]:
        answer = self.command(
            "lookup", expect="providers", service_class=service_class, direction=direction, team=team, player=player
        )
        return [_pairs(p[1:]) for p in answer["_items"]]

    def ping(self) -> None:
        self.command("ping", expect="pong")

    def send(self, msg: AclMessage) -> None:
        self.send_line(acl.to_text(msg))

    def receive(self, deadline: float | None = None) -> AclMessage:
        """The next ACL message for this agent (TimeoutError if none by ``deadline``, monotonic).

        The gateway's own failure or not-understood (about a message sent) raises GatewayError.
        """
        if self.inbox:
            return self.inbox.popleft()
        while True:
            sexp = self.read(deadline)
            head = str(sexp[0]).lower()
            params = _pairs(sexp[1:])
            if head in _PERFORMATIVES and "sender" in params:
                return acl.from_sexp(sexp)
            _raise_if_refused(head, params)

    def request(
        self, receiver: str, content: str, *, protocol: str = "fipa-request", timeout: float = 30.0
    ) -> AclMessage:
        """Run a request or query to its final answer (agree is skipped); return that answer.

        The message carries ``:reply-by`` now + ``timeout`` (wall clock); with no answer by
        then, TimeoutError. Other messages that arrive meanwhile are kept in ``inbox``.
        """
        cid = f"{self.name}-c{next(self._ids)}"
        perf = Performative.QUERY_REF if protocol == "fipa-query" else Performative.REQUEST
        deadline = time.monotonic() + timeout  # our own wait; the wire carries the wall clock
        self.send(
            AclMessage(
                perf,
                receivers=(AgentId(receiver),),
                content=content,
                protocol=protocol,
                conversation_id=cid,
                reply_with=f"{cid}-r1",
                reply_by=time.time() + timeout,
            )
        )
        others: list[AclMessage] = []
        try:
            while True:
                try:
                    msg = self.receive(deadline)
                except TimeoutError:
                    raise TimeoutError(f"no answer from {receiver} within {timeout} s") from None
                if msg.conversation_id != cid:
                    others.append(msg)
                    continue
                if msg.performative is not Performative.AGREE:
                    return msg
        finally:
            self.inbox.extend(others)

    def close(self) -> None:
        with contextlib.suppress(OSError, GatewayError, ValueError):
            self.command("bye", expect="bye")
        self.sock.close()


_PERFORMATIVES = {p.value for p in Performative}


def _pairs(items: list) -> dict:
    out = {}
    for i in range(0, len(items) - 1, 2):
        if type(items[i]) is Keyword:
            out[items[i].name] = items[i + 1]
    return out


def _raise_if_refused(head: str, params: dict) -> None:
    """The gateway's own failure, not-understood or error (it has no :sender) as GatewayError:
    an answer to a command, or a refusal of a message sent (an unknown receiver, say)."""
    if head in ("failure", "not-understood", "error") and "sender" not in params:
        raise GatewayError(f"{head}: {params.get('reason')}")
