"""The gateway core over real TCP sockets, with a fake bus in place of ROS."""

from __future__ import annotations

import asyncio
import socket
import threading
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cf_commag.gateway import Gateway, GatewayConfig
from cf_commag.gateway_client import GatewayClient, GatewayError
from cf_commag.records import Entry, Query
from cf_commag.registry import Registry, Result
from cf_lang.acl import AclMessage, AgentId, Performative


class FakeBus:
    """The framework as the gateway sees it: a real registry core, inboxes as callbacks."""

    def __init__(self):
        self.registry = Registry()
        self.inboxes = {}
        self.published = []
        self.watchers = {}
        self.before_deregister = None  # a test's hook: what happens while the ComMAg answers
        self.unseen = set()

    async def register(self, record) -> Result:
        return self.registry.register(record, now=time.monotonic())[0]

    async def deregister(self, name) -> Result:
        if self.before_deregister is not None:
            self.before_deregister(name)
        return self.registry.deregister(name, now=time.monotonic())[0]

    async def lookup(self, query: Query) -> list[Entry]:
        return self.registry.lookup(query)

    def known(self, name):
        if name in self.unseen:  # registered, but not yet in the snapshot the gateway has
            return False
        return name in self.registry.directory or name in self.inboxes

    def publish(self, receiver, text):
        self.published.append((receiver, text))
        deliver = self.inboxes.get(receiver)
        if deliver is not None:
            deliver(text)

    def open_inbox(self, name, deliver):
        self.inboxes[name] = deliver

    def close_inbox(self, name):
        self.inboxes.pop(name, None)

    def watch_events(self, key, deliver):
        if deliver is None:
            self.watchers.pop(key, None)
        else:
            self.watchers[key] = deliver


class Server:
    """A gateway on its own asyncio loop thread, on an ephemeral loopback port."""

    def __init__(self, **config):
        self.bus = FakeBus()
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()
        self.logs = []
        self.gateway = Gateway(GatewayConfig(port=0, **config), self.bus, log=self.logs.append)
        self.port = asyncio.run_coroutine_threadsafe(self.gateway.start(), self.loop).result(5)

    def on_loop(self, fn, *args):
        self.loop.call_soon_threadsafe(fn, *args)

    def raw(self) -> socket.socket:
        return socket.create_connection(("127.0.0.1", self.port), timeout=10)

    def client(self, name, **kw) -> GatewayClient:
        return GatewayClient("127.0.0.1", self.port, name=name, **kw)

    def stop(self):
        asyncio.run_coroutine_threadsafe(self.gateway.stop(), self.loop).result(5)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5)


@pytest.fixture
def server():
    s = Server(max_line_bytes=4096, max_depth=16, max_queue=50, max_pending_bytes=256 * 1024, hello_timeout=2.0)
    yield s
    s.stop()


def lines(sock: socket.socket, count: int) -> list[str]:
    data = b""
    while data.count(b"\n") < count:
        chunk = sock.recv(65536)
        if not chunk:
            break
        data += chunk
    return [line for line in data.decode(errors="replace").split("\n") if line]


def until_pong(sock: socket.socket) -> list[str]:
    """Read lines until (pong) or a final (error ...)."""
    data = b""
    while True:
        got = [line for line in data.decode(errors="replace").split("\n") if line]
        if any(g == "(pong)" or g.startswith("(error") for g in got):
            return got
        chunk = sock.recv(65536)
        if not chunk:
            return got
        data += chunk


def test_binds_loopback_and_reports_its_port(server):
    assert server.gateway.config.host == "127.0.0.1" and server.port > 0


def test_session_register_lookup_and_relay(server):
    with server.client("alice") as alice, server.client("bob") as bob:
        assert alice.welcome["version"] == 1
        assert alice.register("Kick", team="blue", player=3) == 2.0
        assert [p["name"] for p in bob.lookup("Shoot", team="blue")] == ["alice"]  # Kick serves Shoot
        assert [p["name"] for p in bob.lookup("Action")] == []  # ... but not any Action
        assert [p["name"] for p in bob.lookup("Action", direction="specific")] == ["alice"]
        record = server.bus.registry.directory.get("alice").record
        assert record.transport.value == "tcp" and record.launch_command == () and record.address == "127.0.0.1"
        bob.send(
            AclMessage(
                Performative.INFORM, receivers=(AgentId("alice"),), content="(Game :time 1)", conversation_id="c1"
            )
        )
        got = alice.receive()
        assert got.sender == AgentId("bob") and got.content == "(Game :time 1)"
        alice.ping()


@pytest.mark.parametrize(
    ("line", "answer"),
    [
        (b"(((", "not-understood :reason \"unclosed '('"),
        (b"\xff\xfe garbage", 'not-understood :reason "invalid UTF-8'),
        (b"(" * 40 + b")" * 40, 'not-understood :reason "nesting too deep'),
        (b"hello", 'not-understood :reason "expected (command'),
        (b"(dance :now 1)", 'not-understood :reason "unknown command dance'),
        (b"(register :service-class Juggle)", 'failure :in-reply-to "register" :reason "unknown service class'),
        (b'(register :service-class Kick :launch-command (sequence "/bin/sh"))', "cannot register a launch command"),
        (b"(lookup :service-class Kick :direction sideways)", "direction must be one of"),
        (b'(inform :receiver nobody :content "x")', "unknown receiver nobody"),
        (b'(inform :sender mallory :receiver alice :content "x")', "you are carol, not mallory"),
        (b"(inform :receiver)", "not-understood"),
        # The same checks on lines of the common shape, which take the fast reader:
        (b'(inform :receiver (set (agent-identifier :name nobody)) :content "x")', "unknown receiver nobody"),
        (
            b"(inform :sender (agent-identifier :name mallory) :receiver (set (agent-identifier :name alice)))",
            "you are carol, not mallory",
        ),
        (b'(inform :content "x")', 'failure :in-reply-to "inform" :reason "no :receiver'),
        (b"(inform :receiver (set (agent-identifier :name alice)) :reply-by 20261341T101010123Z)", "not a valid"),
        (b"(shout :receiver (set (agent-identifier :name alice)))", "unknown command shout"),
        (b"(hello :name carol)", "already connected as carol"),
    ],
)
def test_bad_input_is_answered_and_the_connection_stays(server, line, answer):
    with server.client("alice"):
        sock = server.raw()
        sock.sendall(b"(hello :name carol)\n" + line + b"\n(ping)\n")
        got = lines(sock, 3)
        assert got[0].startswith("(welcome")
        assert answer in got[1], got[1]
        assert got[2] == "(pong)"
        sock.close()


def test_an_agent_a_lookup_named_is_reachable_before_the_snapshot_shows_it(server):
    """The registry snapshot reaches the gateway a moment after the ComMAg answers: an agent
    that registered just now is missing from it, but once a lookup has named it, messages to
    it go through. A name no lookup gave is still refused while the snapshot lacks it."""
    with server.client("alice") as alice, server.client("bob") as bob, server.client("carol") as carol:
        alice.register("Kick", team="blue")
        carol.register("Hearing", team="blue")
        server.bus.unseen |= {"alice", "carol"}  # registered, not yet in the gateway's snapshot
        line = '(inform :receiver (set (agent-identifier :name {})) :content "(Game :time 1)")'
        bob.send_line(line.format("carol"))
        with pytest.raises(GatewayError, match="unknown receiver carol"):
            bob.receive()
        assert [p["name"] for p in bob.lookup("Kick", team="blue")] == ["alice"]
        bob.send_line(line.format("alice"))
        assert alice.receive().content == "(Game :time 1)"


def test_a_request_nobody_answers_ends_at_its_reply_by_and_keeps_what_came_meanwhile(server):
    with server.client("alice") as alice, server.client("bob") as bob:
        alice.register("Kick", team="blue")
        bob.register("Hearing", team="blue")
        asked = []

        def take_it_and_talk_of_something_else():
            asked.append(alice.receive())
            alice.send(AclMessage(Performative.INFORM, receivers=(AgentId("bob"),), content="(meanwhile)"))

        helper = threading.Thread(target=take_it_and_talk_of_something_else)
        helper.start()
        with pytest.raises(TimeoutError, match=r"no answer from alice within 0\.5 s"):
            bob.request("alice", "(exec Player kick :playerNumber 9 :whichTeam our :power 10)", timeout=0.5)
        helper.join(10)
        assert asked[0].performative is Performative.REQUEST
        assert time.time() - 10 < asked[0].reply_by < time.time() + 10  # the wall clock, not a monotonic one
        bob.ping()  # the timed-out wait left the connection usable
        assert bob.receive().content == "(meanwhile)"  # kept in the inbox, not dropped


def test_commands_before_hello_and_bad_names(server):
    sock = server.raw()
    sock.sendall(b"(ping)\n(hello :name 7up)\n(hello :name ok_name)\n")
    got = lines(sock, 3)
    assert "say (hello :name ...) first" in got[0]
    assert "must match" in got[1]
    assert got[2].startswith("(welcome")


def test_oversized_line_closes_with_a_final_error(server):
    sock = server.raw()
    sock.sendall(b"(hello :name big)\n(ping " + b"x" * 10_000 + b")\n")
    got = lines(sock, 5)
    assert got[0].startswith("(welcome")
    assert got[-1].startswith("(error") and "longer than 4096 bytes" in got[-1]
    assert sock.recv(100) == b""  # closed


def test_the_final_error_line_survives_lines_the_client_sent_after_it(server):
    # The client goes on writing after the line that ends its connection. Closing a socket
    # with unread input makes the kernel reset it, and the reset can destroy the error line.
    sock = server.raw()
    sock.sendall(b"(hello :name talker)\n(ping " + b"x" * 10_000 + b")\n" + b"(ping)\n" * 20_000)
    time.sleep(0.5)  # the gateway has written its last line and closed its side
    received = sock.makefile("rb").read().decode().splitlines()  # until the gateway closes
    assert received[0].startswith("(welcome")
    assert received[-1].startswith("(error") and "longer than 4096 bytes" in received[-1]
    assert "(pong)" not in received


def test_disconnect_mid_line_releases_everything(server):
    sock = server.raw()
    sock.sendall(b"(hello :name halfway)\n(register :service-class Kick)\n(ping :half")
    lines(sock, 2)
    assert "halfway" in server.bus.inboxes
    sock.close()
    deadline = time.monotonic() + 5
    while "halfway" in server.bus.inboxes and time.monotonic() < deadline:
        time.sleep(0.01)
    assert "halfway" not in server.bus.inboxes and "halfway" not in server.gateway.sessions
    # The ComMAg decides about the component: the gateway stops renewing it.
    assert server.gateway.due_renewals(time.monotonic()) == []


def test_wrong_token_is_refused_and_closed():
    server = Server(token="s3cret")
    try:
        with pytest.raises(GatewayError, match="wrong token"):
            server.client("intruder", token="guess")
        with server.client("friend", token="s3cret") as ok:
            ok.ping()
    finally:
        server.stop()


def test_a_wrong_token_closes_after_a_final_error_line():
    server = Server(token="s3cret")
    try:
        sock = server.raw()
        sock.sendall(b'(hello :name intruder :token "guess")\n')
        lines = sock.makefile("rb").read().decode().splitlines()  # until the gateway closes
        assert lines == ['(failure :in-reply-to "hello" :reason "wrong token")', '(error :reason "wrong token")']
    finally:
        server.stop()


def test_silent_connection_must_say_hello_in_time(server):
    sock = server.raw()
    got = lines(sock, 1)
    assert "no hello within 2.0 s" in got[0]


def test_too_many_connections():
    server = Server(max_connections=1)
    try:
        with server.client("first"):
            sock = server.raw()
            assert "too many connections" in lines(sock, 1)[0]
    finally:
        server.stop()


def test_a_reader_that_never_reads_is_cut_off_and_others_keep_being_served(server):
    slow = server.raw()
    slow.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    slow.sendall(b"(hello :name sloth)\n")
    lines(slow, 1)
    with server.client("fast") as fast:
        deliver = server.bus.inboxes["sloth"]
        big = '(inform :sender x :content "' + "y" * 2000 + '")'
        for _ in range(5000):  # 10 MB: far more than the socket buffers and the limits hold
            server.on_loop(deliver, big)
            fast.ping()  # the fast client is answered all along
        deadline = time.monotonic() + 10
        while "sloth" in server.gateway.sessions and time.monotonic() < deadline:
            fast.ping()
        assert "sloth" not in server.gateway.sessions
        assert server.gateway.slow_disconnects == 1
        fast.ping()


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.binary(max_size=200).filter(lambda b: b"\n" not in b), min_size=1, max_size=5))
def test_fuzzed_frames_never_break_the_gateway(server, frames):
    sock = server.raw()
    sock.sendall(b"(hello :name fuzz)\n" + b"\n".join(frames) + b"\n(ping)\n")
    got = until_pong(sock)
    assert got[0].startswith("(welcome")
    assert got[-1] == "(pong)" or got[-1].startswith("(error")
    sock.close()
    deadline = time.monotonic() + 5
    while "fuzz" in server.gateway.sessions and time.monotonic() < deadline:
        time.sleep(0.01)
    with server.client("after_fuzz") as c:
        c.ping()


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    st.sampled_from(
        [
            b"(hello :name m)",
            b"(register :service-class Kick)",
            b"(lookup :service-class Kick)",
            b'(inform :receiver m :content "x")',
            b"(ping)",
        ]
    ),
    st.integers(0, 40),
    st.binary(min_size=1, max_size=3),
)
def test_mutated_frames(server, frame, at, junk):
    mutated = (frame[:at] + junk + frame[at:]).replace(b"\n", b" ")
    sock = server.raw()
    sock.sendall(b"(hello :name mut)\n" + mutated + b"\n(ping)\n")
    got = until_pong(sock)
    assert got[0].startswith("(welcome") and got[-1] == "(pong)"
    sock.close()
    deadline = time.monotonic() + 5
    while "mut" in server.gateway.sessions and time.monotonic() < deadline:
        time.sleep(0.01)


def test_a_burst_goes_out_as_one_sample_per_receiver(server):
    with server.client("alice"), server.client("carol"):
        sock = server.raw()
        burst = b"".join(
            b'(inform :receiver %s :content "%d")\n' % (to, i) for i in range(6) for to in (b"alice", b"carol")
        )
        sock.sendall(b"(hello :name bob)\n" + burst + b"(ping)\n")
        got = until_pong(sock)
        assert got[0].startswith("(welcome") and got[-1] == "(pong)"
        deadline = time.monotonic() + 5  # published at the end of the loop turn, maybe after the pong
        while sum(t.count("\n") + 1 for _, t in server.bus.published) < 12 and time.monotonic() < deadline:
            time.sleep(0.01)
        samples = {to: [t for r, t in server.bus.published if r == to] for to in ("alice", "carol")}
        for to, texts in samples.items():
            lines_ = [line for t in texts for line in t.split("\n")]
            assert [line.rsplit('"', 2)[1] for line in lines_] == [str(i) for i in range(6)], to
        # One read brought the whole burst, so each receiver got it in fewer samples than messages.
        assert len(samples["alice"]) < 6 and len(samples["carol"]) < 6
        sock.close()


def test_inbox_samples_delivered_from_another_thread_arrive_whole_and_in_order(server):
    with server.client("alice") as alice:
        deliver = server.bus.inboxes["alice"]
        sent = [f'(inform :sender bob :receiver alice :content "{i}")' for i in range(3000)]

        def ros_thread():  # like the gateway node's executor thread
            for i in range(0, len(sent), 3):
                deliver("\n".join(sent[i : i + 3]))

        t = threading.Thread(target=ros_thread)
        t.start()
        got = [alice.receive().content for _ in range(len(sent))]
        t.join()
        assert got == [str(i) for i in range(3000)]
        alice.ping()  # and the gateway's own answers still come through


def test_bye_comes_after_every_message_still_waiting_to_be_written():
    """An inbox message the socket could not take at once waits for the loop thread;
    a (bye) handled before that write must not close the connection over it."""
    server = Server(max_pending_bytes=64 * 1024 * 1024)
    try:
        big = '(inform :sender bob :receiver alice :content "' + "x" * (8 * 1024 * 1024) + '")'
        # Delivered while the ComMAg answers the bye; bigger than the largest kernel send buffer
        # (4 MiB by default), so part of it always waits for the loop thread.
        server.bus.before_deregister = lambda name: server.bus.inboxes[name](big)
        sock = socket.socket()
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)  # a small window: the send is partial
        sock.settimeout(10)
        sock.connect(("127.0.0.1", server.port))
        sock.sendall(b"(hello :name alice)\n(register :service-class Kick :team blue :player 9)\n(bye)\n")
        data = b""
        while chunk := sock.recv(1 << 20):
            data += chunk
        got = data.decode().split("\n")
        assert got[-3:] == [big, "(bye)", ""], [f"{g[:40]}... ({len(g)} chars)" for g in got]
        sock.close()
    finally:
        server.stop()


@pytest.mark.parametrize(
    "line",
    [
        b'(INFORM :receiver alice :content "x" :conversation-id c1)',
        b'  (  inform   :receiver (set (agent-identifier :name alice)) :content "x" :conversation-id c1 )  \r',
        b'(inform :sender (agent-identifier :name bob) :receiver alice :content "x" :conversation-id c1)',
    ],
)
def test_relayed_lines_carry_their_sender(server, line):
    with server.client("alice") as alice:
        sock = server.raw()
        sock.sendall(b"(hello :name bob)\n" + line + b"\n(ping)\n")
        until_pong(sock)
        got = alice.receive()
        assert got.sender == AgentId("bob") and got.content == "x" and got.conversation_id == "c1"
        sock.close()
