"""A player's action component: executes (exec Player <method> ...) requests, cycle by cycle."""

from __future__ import annotations

import json
import sys

from std_msgs.msg import String

from cf_commag.runtime import run
from cf_sim_backend.embedded.player_base import PlayerComponentNode
from cf_sim_backend.embedded.topics import COMMAND_QOS, command_topic, encode_command
from cf_sim_backend.services import ActionService
from cf_sim_backend.world import World


class ActionNode(PlayerComponentNode):
    """Action of one player (service class Action) on the embedded simulator. Parameters: PlayerParams.

    Requests are served by :class:`ActionService` (shared with the rcssserver adapter); this node
    steps the current skill every cycle and publishes its commands to the simulator.
    """

    ROLE = "action"
    SERVICE_CLASS = "Action"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.commands = self.create_publisher(String, command_topic(self.p.sim), COMMAND_QOS)
        self.action = ActionService(
            self.agent, lambda: (self.number, self.side), lambda: self.world, "the simulator has not started"
        )

    def on_cycle(self, world: World) -> None:
        self._act(world)
        if self.step is not None:  # tell the simulator we are done with this cycle (its sync mode)
            done = {"side": self.side.value, "number": self.number, "done": self.step}
            self.commands.publish(String(data=json.dumps(done)))

    def _act(self, world: World) -> None:
        if not self.action.active:
            return
        skill = self.action.skill
        step = skill.step(world, world.player(self.side, self.number))
        for cmd in step.commands:
            self.commands.publish(String(data=encode_command(self.side.value, self.number, cmd[0], cmd[1:])))
        self.action.settle(step.status, step.reason, skill.name, skill.cycles)


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend action``."""
    return run(ActionNode)


if __name__ == "__main__":
    sys.exit(main())
