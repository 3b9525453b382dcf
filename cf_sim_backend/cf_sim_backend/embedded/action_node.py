"""A player's action component: executes (exec Player <method> ...) requests, cycle by cycle."""

from __future__ import annotations

import sys

from cf_commag.runtime import run
from cf_sim_backend.embedded.player_base import PlayerComponentNode
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
        self.action = ActionService(
            self.agent,
            lambda: (self.number, self.side),
            self._my_world,
            "the simulator has not started",
            on_say=self._say,
        )

    def _say(self, text: str) -> None:
        """Sent with this player's next commands: team-mates within audio_cut_dist hear it the cycle after."""
        self.feed.command({"side": self.side.value, "number": self.number, "cmd": "say", "args": [text]})

    def _my_world(self) -> World | None:
        """The current world with my type's parameters: what the skills read (World.as_player)."""
        if self.world is None:
            return None
        return self.world.as_player(self.world.player(self.side, self.number))

    def on_cycle(self, world: World) -> None:
        self._act()
        if self.step is not None:  # tell the simulator we are done with this cycle (its sync mode)
            self.feed.command({"side": self.side.value, "number": self.number, "done": self.step})

    def _act(self) -> None:
        """Step the current skill on this cycle's world (the base class has just set ``self.world``)."""
        if not self.action.active:
            return
        skill = self.action.skill
        mine = self._my_world()
        step = skill.step(mine, mine.player(self.side, self.number))
        for cmd in step.commands:
            self.feed.command({"side": self.side.value, "number": self.number, "cmd": cmd[0], "args": list(cmd[1:])})
        self.action.settle(step.status, step.reason, skill.name, skill.cycles)


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend action``."""
    return run(ActionNode)


if __name__ == "__main__":
    sys.exit(main())
