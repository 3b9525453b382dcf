"""A player's perception component: answers (val ...) queries and informs subscribers every cycle."""

from __future__ import annotations

import random
import sys

from cf_commag.runtime import run
from cf_sim_backend.embedded.player_base import PlayerComponentNode
from cf_sim_backend.perception import observe
from cf_sim_backend.services import PerceptionService
from cf_sim_backend.world import World


class PerceptionNode(PlayerComponentNode):
    """Perception of one player (service class WorldModel). Parameters: PLAYER_PARAMS, noise, seed."""

    ROLE = "perception"
    SERVICE_CLASS = "WorldModel"

    def __init__(self, **kwargs):
        super().__init__(
            {
                "noise": (0.02, "position noise: standard deviation per metre of distance"),
                "seed": (0, "random seed of the noise"),
            },
            **kwargs,
        )
        self.rng = random.Random(int(self.p["seed"]) * 100 + self.number + (0 if self.p["side"] == "l" else 50))
        self.perception = PerceptionService(self.agent, "the simulator has not started")

    def on_cycle(self, world: World) -> None:
        self.perception.publish(observe(world, self.side, self.number, self.rng, noise=float(self.p["noise"])))


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend perception``."""
    return run(PerceptionNode)


if __name__ == "__main__":
    sys.exit(main())
