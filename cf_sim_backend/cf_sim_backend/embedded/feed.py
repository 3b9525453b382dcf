"""The simulator's link to the player components of one process: its state read once, commands sent once.

Every player component needs the state the simulator publishes each cycle (4 KB of JSON) and the
action components send it commands. A process that hosts several components reads each state
once, hands the same :class:`World` to all of them, and sends their commands of the cycle back
as one sample (a JSON list) when they are done, instead of one subscription, one parse and
several samples per component.
"""

from __future__ import annotations

import json
from collections.abc import Callable

from rclpy.node import Node
from std_msgs.msg import String

from cf_sim_backend.embedded.topics import COMMAND_QOS, STATE_QOS, command_topic, state_topic
from cf_sim_backend.world import World, world_from_snapshot

Listener = Callable[[World, "int | None"], None]


class StateFeed:
    """The state subscription and command publisher shared by the player components on ``node``'s process."""

    def __init__(self, node: Node, sim: str):
        self._node = node
        self._listeners: list[Listener] = []
        self._pending: list[dict] = []
        self.world: World | None = None
        self.step: int | None = None  # the simulator's step counter, for its sync mode
        self._commands = node.create_publisher(String, command_topic(sim), COMMAND_QOS)
        node.create_subscription(String, state_topic(sim), self._on_state, STATE_QOS)

    def listen(self, listener: Listener) -> None:
        """Call ``listener(world, step)`` for every state."""
        self._listeners.append(listener)

    def command(self, command: dict) -> None:
        """Queue a command (``{"side", "number", "cmd", "args"}`` or a sync ``done``) for this cycle's sample."""
        self._pending.append(command)

    def _on_state(self, msg: String) -> None:
        try:
            data = json.loads(msg.data)
            world = world_from_snapshot(data)
            step = data.get("step")
        except (ValueError, KeyError, TypeError) as exc:
            self._node.get_logger().error(f"bad state from the simulator: {exc}", throttle_duration_sec=5.0)
            return
        self.world, self.step = world, step
        log = self._node.get_logger()
        for listener in self._listeners:
            try:
                listener(world, step)
            except Exception as exc:  # one component's error must not cost the others their cycle
                log.error(f"{getattr(listener, '__qualname__', listener)} failed: {exc!r}", throttle_duration_sec=5.0)
        self.send()

    def send(self) -> None:
        """Publish what was queued as one sample."""
        if self._pending:
            batch, self._pending = self._pending, []
            self._commands.publish(String(data=json.dumps(batch if len(batch) > 1 else batch[0])))
