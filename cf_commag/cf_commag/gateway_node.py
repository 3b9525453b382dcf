"""The gateway as a ROS node: the asyncio TCP server in its own thread, rclpy in the main one."""

from __future__ import annotations

import asyncio
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Literal

from pydantic import Field
from rclpy.node import Node
from std_msgs.msg import String

from cf_interfaces.msg import Registry as RegistryMsg
from cf_interfaces.msg import RegistryEvent
from cf_interfaces.srv import Deregister, Lookup, Register

from .convert import directory_from_msg, entry_from_msg, query_to_request, to_msg
from .gateway import Gateway, GatewayConfig, form
from .guarded import GuardedNode
from .params import NodeParams
from .records import Entry, Query, Record
from .registry import Result
from .renewer import Renewer
from .runtime import make_executor, run
from .transport.outbox import Outbox, inbox_topic, sample_text
from .transport.qos import EVENTS_QOS, INBOX_QOS, SERVICE_QOS, SNAPSHOT_QOS


class GatewayParams(NodeParams):
    """The gateway's parameters; all but the last three make its GatewayConfig."""

    host: str = Field("127.0.0.1", description="address to listen on (loopback unless told otherwise)")
    port: int = Field(
        7700, ge=0, le=65535, description="TCP port; 0 picks a free one (reported in the log and in port_file)"
    )
    token: str = Field("", description="if set, agents must give it in hello")
    max_connections: int = Field(256, ge=1, description="connections served at once")
    max_line_bytes: int = Field(65536, ge=256, description="longest line accepted; longer ones close the connection")
    max_depth: int = Field(32, ge=2, description="deepest S-expression nesting accepted")
    max_queue: int = Field(10000, ge=1, description="lines queued for one agent before it is disconnected as too slow")
    max_pending_bytes: int = Field(
        4 << 20, ge=1024, description="unsent bytes for one agent before it is disconnected as too slow"
    )
    default_lease: float = Field(2.0, gt=0, description="lease (s) for agents that do not ask for one")
    hello_timeout: float = Field(10.0, gt=0, description="seconds a new connection has to say hello")
    commag: str = Field("/commag", description="the ComMAg's node name")
    port_file: str = Field("", description="if set, the bound port is written to this file")
    executor: Literal["events", "single"] = Field(
        "events", description="rclpy executor: events (rclpy.experimental.EventsExecutor) or single"
    )


class GatewayNode(GuardedNode, Node):
    """TCP socket gateway: makes TCP agents full members of the framework.

    Parameters: GatewayParams.
    Uses the ComMAg's ``register``/``deregister``/``lookup`` services and
    ``registry``/``events`` topics; publishes to and subscribes on
    ``/cf/agents/<name>/inbox`` for its agents.
    """

    def __init__(self, **kwargs):
        super().__init__("gateway", **kwargs)
        p = GatewayParams.declare_and_read(self)
        self.config = GatewayConfig(**p.model_dump(exclude={"commag", "port_file", "executor"}))
        commag = p.commag
        self._register = self.create_client(Register, f"{commag}/register", qos_profile=SERVICE_QOS)
        self._deregister = self.create_client(Deregister, f"{commag}/deregister", qos_profile=SERVICE_QOS)
        self._lookup = self.create_client(Lookup, f"{commag}/lookup", qos_profile=SERVICE_QOS)
        self._known: frozenset[str] = frozenset()  # agents not withdrawn, from the registry snapshot
        self.create_subscription(RegistryMsg, f"{commag}/registry", self._on_snapshot, SNAPSHOT_QOS)
        self.create_subscription(RegistryEvent, f"{commag}/events", self._on_event, EVENTS_QOS)
        self._outbox = Outbox(self)
        self._inboxes: dict[str, object] = {}
        self._watchers: dict[object, Callable[[str], None]] = {}
        self._renewer = Renewer(self._register)
        # Subscriptions are created and destroyed on the executor thread (not thread-safe);
        # the asyncio thread leaves that work here. Publishing and service calls are
        # thread-safe and happen on the asyncio thread directly, without a hop.
        self._todo: list[Callable[[], None]] = []
        self._todo_lock = threading.Lock()
        self.create_timer(0.02, self._run_todo)
        self.create_timer(0.1, self._renew_due)
        self.loop = asyncio.new_event_loop()
        self.gateway = Gateway(self.config, self, log=self.get_logger().error)
        self._thread = threading.Thread(target=self.loop.run_forever, name="gateway-asyncio", daemon=True)
        self._thread.start()
        port = asyncio.run_coroutine_threadsafe(self.gateway.start(), self.loop).result(timeout=10)
        self.get_logger().info(f"gateway listening on {self.config.host}:{port}")
        if p.port_file:
            # Written whole then renamed: whoever waits for the file never reads it empty.
            tmp = Path(f"{p.port_file}.tmp")
            tmp.write_text(f"{port}\n")
            tmp.replace(p.port_file)

    # ---- thread hand-off ----------------------------------------------------

    def _on_ros(self, fn: Callable[[], None]) -> None:
        with self._todo_lock:
            self._todo.append(fn)

    def _run_todo(self) -> None:
        self._outbox.flush()
        if not self._todo:
            return
        with self._todo_lock:
            todo, self._todo = self._todo, []
        for fn in todo:
            fn()

    def _to_loop(self, fn: Callable, *args) -> None:
        self.loop.call_soon_threadsafe(fn, *args)

    async def _call(self, client, request, timeout: float = 5.0):
        """A ROS service call awaited from the asyncio side (waits for the ComMAg to be discovered)."""
        deadline = time.monotonic() + timeout
        while not client.service_is_ready():
            if time.monotonic() > deadline:
                raise RuntimeError("the ComMAg is not reachable")
            await asyncio.sleep(0.05)
        return await asyncio.wait_for(self._start_call(client, request), max(0.1, deadline - time.monotonic()))

    def _start_call(self, client, request) -> asyncio.Future:
        result: asyncio.Future = self.loop.create_future()

        def settle(ok: bool, value) -> None:
            if not result.done():
                result.set_result(value) if ok else result.set_exception(value)

        future = client.call_async(request)  # rclpy clients may be called from any thread
        future.add_done_callback(lambda f: self._to_loop(settle, f.exception() is None, f.exception() or f.result()))
        return result

    # ---- the Bus ------------------------------------------------------------

    async def register(self, record: Record) -> Result:
        try:
            res = await self._call(self._register, Register.Request(component=to_msg(record)))
        except (TimeoutError, RuntimeError) as exc:
            return Result(False, f"ComMAg did not answer: {exc or 'timeout'}")
        if res.accepted:
            self._renewer.registered(record.name, time.monotonic())
        return Result(res.accepted, res.reason, res.lease_period)

    async def deregister(self, name: str) -> Result:
        self._renewer.forget(name)
        try:
            res = await self._call(self._deregister, Deregister.Request(name=name))
        except (TimeoutError, RuntimeError) as exc:
            return Result(False, f"ComMAg did not answer: {exc or 'timeout'}")
        return Result(res.accepted, res.reason)

    async def lookup(self, query: Query) -> list[Entry]:
        request = query_to_request(query)
        try:
            res = await self._call(self._lookup, request)
        except (TimeoutError, RuntimeError) as exc:
            raise ValueError(f"ComMAg did not answer: {exc or 'timeout'}") from None
        if not res.ok:
            raise ValueError(res.reason)
        return [entry_from_msg(p) for p in res.providers]

    def known(self, name: str) -> bool:
        return name in self._known

    def publish(self, receiver: str, text: str) -> None:
        self._outbox.send(receiver, text)

    def open_inbox(self, name: str, deliver: Callable[[str], bool]) -> None:
        def on_message(sample: bytes) -> None:
            # On the executor thread: the gateway writes it to the socket from here.
            # A sample may hold several messages, one per line: the gateway's wire format too.
            deliver(sample_text(sample))

        def create() -> None:
            self._inboxes[name] = self.create_subscription(String, inbox_topic(name), on_message, INBOX_QOS, raw=True)

        self._on_ros(create)

    def close_inbox(self, name: str) -> None:
        def destroy() -> None:
            sub = self._inboxes.pop(name, None)
            if sub is not None:
                self.destroy_subscription(sub)

        self._renewer.forget(name)
        self._on_ros(destroy)

    def watch_events(self, key: object, deliver: Callable[[str], None] | None) -> None:
        if deliver is None:
            self._watchers.pop(key, None)
        else:
            self._watchers[key] = deliver

    # ---- ROS callbacks ------------------------------------------------------

    def _on_snapshot(self, msg: RegistryMsg) -> None:
        # Asked once per relayed message: a set, made once per snapshot.
        entries = directory_from_msg(msg).entries()
        self._known = frozenset(e.name for e in entries if e.state.value != "withdrawn")
        self._outbox.retain(self._known)  # publishers to agents that are gone are released

    def _on_event(self, ev: RegistryEvent) -> None:
        if not self._watchers:
            return
        line = form(
            "event",
            kind=ev.kind_name,
            name=ev.record.name,
            service_class=ev.record.service_class,
            state=ev.record.state,
            team=ev.record.team,
            player=ev.record.player_number,
            reason=ev.reason,
        )
        for deliver in list(self._watchers.values()):
            self._to_loop(deliver, line)

    def _renew_due(self) -> None:
        """Renew the agents that showed life within their lease, three times per lease."""
        now = time.monotonic()
        for record in self.gateway.due_renewals(now):
            if self._renewer.due(record.name, record.lease_period, now):
                self._renewer.send(record.name, Register.Request(component=to_msg(record)), now)

    def shutdown(self) -> None:
        asyncio.run_coroutine_threadsafe(self.gateway.stop(), self.loop).result(timeout=5)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self._thread.join(timeout=5)


def _executor(node: GatewayNode):
    executor = make_executor(node.get_parameter("executor").value)
    executor.add_node(node)
    return executor


def main(args: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_commag gateway``."""
    return run(GatewayNode, executor=_executor, on_exit=GatewayNode.shutdown, args=args)


if __name__ == "__main__":
    sys.exit(main())
