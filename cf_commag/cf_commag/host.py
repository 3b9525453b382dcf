"""Agents that share a process: their link to the ComMAg, one clock, and delivery without DDS.

    host = Host(container_node, name="blue_players")          # one per process
    perception = Agent(node_a, name="blue_7_perception", ..., host=host)
    decision = Agent(node_b, name="blue_7_decision", ..., host=host)

ROS 2 calls this composition: one process (a component container) holds several nodes. Each
hosted agent stays an agent of its own (name, registration, lease, inbox topic on DDS, found
by lookup), but the process pays once for what all of them need:

- one set of ComMAg clients and one registry snapshot subscription (the lookup cache);
- one timer (every ``tick`` seconds) that renews each agent's lease when due, expires its
  conversations and retries what waits for a receiver's inbox;
- one Outbox: one publisher per remote receiver, whichever hosted agent sends;
- **local delivery**: a message from one hosted agent to another is handed over as the
  message it is (no text written, no DDS sample, no parse), after the callback that sent it
  returns (never from inside it, so a handler never runs inside another's half-done work).
  Messages from other processes still arrive through the agent's inbox.

A hosted agent's record names its host (``host`` metadata) and its process (``pid``,
``started``), so the ComMAg relaunches a dead host once for all its agents and can tell a
process that is alive but silent (starved or hung) from one that is gone.

A standalone agent gets a private host of its own: the same code, one agent.
"""

from __future__ import annotations

import os
import threading
import time
from collections import deque
from typing import TYPE_CHECKING

from rclpy.node import Node

from cf_interfaces.msg import Registry as RegistryMsg
from cf_interfaces.srv import Deregister, Lookup, Register
from cf_lang.acl import AclMessage

from .convert import directory_from_msg
from .guarded import GuardedNode, call_when_idle, guard, in_callback
from .records import Directory
from .renewer import Renewer
from .transport.outbox import Outbox
from .transport.qos import SERVICE_QOS, SNAPSHOT_QOS

if TYPE_CHECKING:
    from .agent import Agent


class Host:
    """The agents of one process (see the module docstring). ``node`` carries the shared parts."""

    def __init__(
        self,
        node: Node,
        *,
        name: str = "",
        commag: str = "/commag",
        tick: float = 0.1,
        watchdog: float = 0.0,
    ):
        self.node = node
        self.name = name
        self.commag = commag
        self.agents: dict[str, Agent] = {}
        self.delivered = 0  # messages handed over locally
        self._log = node.get_logger()
        self._queue: deque[tuple[Agent, AclMessage]] = deque()
        self._delivery_due = False

        def guarded(callback):  # a GuardedNode guards what it creates; a plain node does not
            return callback if isinstance(node, GuardedNode) else guard(callback, self._log, callback.__qualname__)

        self.register_client = node.create_client(Register, f"{commag}/register", qos_profile=SERVICE_QOS)
        self.renewer = Renewer(self.register_client)
        self.deregister_client = node.create_client(Deregister, f"{commag}/deregister", qos_profile=SERVICE_QOS)
        self.lookup_client = node.create_client(Lookup, f"{commag}/lookup", qos_profile=SERVICE_QOS)
        self.directory = Directory()
        self._snapshot_sub = node.create_subscription(
            RegistryMsg, f"{commag}/registry", guarded(self._on_snapshot), SNAPSHOT_QOS
        )
        self.outbox = Outbox(node)
        self.last_tick = time.monotonic()
        self._tick_timer = node.create_timer(tick, guarded(self._on_tick))
        if watchdog > 0:
            threading.Thread(target=self._watch, args=(watchdog,), name="host-watchdog", daemon=True).start()

    # ---- agents -----------------------------------------------------------------

    def add(self, agent: Agent) -> None:
        if agent.me.name in self.agents:
            raise ValueError(f"{self.name or 'this process'} already hosts an agent named {agent.me.name!r}")
        self.agents[agent.me.name] = agent

    def remove(self, agent: Agent) -> None:
        if self.agents.get(agent.me.name) is agent:
            del self.agents[agent.me.name]

    def _on_snapshot(self, msg: RegistryMsg) -> None:
        self.directory = directory_from_msg(msg)

    def _on_tick(self) -> None:
        now = time.monotonic()
        self.last_tick = now
        self.outbox.flush()
        for agent in list(self.agents.values()):
            agent.on_tick(now)

    # ---- local delivery ---------------------------------------------------------

    def local(self, name: str) -> Agent | None:
        """The hosted agent named ``name``, if it lives here."""
        return self.agents.get(name)

    def post(self, receiver: Agent, message: AclMessage) -> None:
        """Deliver ``message`` to a hosted agent once the running callback has returned."""
        self._queue.append((receiver, message))
        if not in_callback():  # sent from outside any callback (a script, a test): deliver now
            self._deliver()
        elif not self._delivery_due:
            self._delivery_due = True
            call_when_idle(self._deliver)

    def _deliver(self) -> None:
        # Delivered as a callback of its own: what the receivers send meanwhile joins this round.
        self._delivery_due = True
        try:
            guard(self._deliver_queued, self._log, "local delivery")()
        finally:
            self._delivery_due = False

    def _deliver_queued(self) -> None:
        queue = self._queue
        while queue:
            receiver, message = queue.popleft()
            self.delivered += 1
            receiver.receive(message)

    # ---- hang detection ---------------------------------------------------------

    def _watch(self, limit: float) -> None:
        """End the process if its callbacks stopped running: a hung host is relaunched, not left to linger.

        A starved process still ticks now and then; one that has not ticked for ``limit`` seconds
        is stuck in a callback. Its agents' leases have run out long before: the ComMAg relaunches
        it, and a hung old process would keep its inboxes (and the messages sent to them) for ever.
        """
        while True:
            time.sleep(min(1.0, limit / 4))
            silent = time.monotonic() - self.last_tick
            if silent > limit:
                self._log.fatal(f"no callback ran for {silent:.1f} s (hung): exiting so that the ComMAg relaunches")
                os._exit(70)
