"""A player's perception component: answers (val ...) queries and informs subscribers every cycle."""

from __future__ import annotations

import random
import sys

from pydantic import Field

from cf_commag.runtime import run
from cf_sim_backend.embedded.player_base import PlayerComponentNode, PlayerParams
from cf_sim_backend.memory import Memory
from cf_sim_backend.perception import observe
from cf_sim_backend.services import PerceptionService
from cf_sim_backend.world import World


class PerceptionParams(PlayerParams):
    noise: float = Field(0.02, ge=0, description="position noise: standard deviation per metre of distance")
    seed: int = Field(0, description="random seed of the noise")
    memory: bool = Field(True, description="tell the players and ball seen lately too, as on rcssserver (memory.py)")


class PerceptionNode(PlayerComponentNode):
    """Perception of one player (service class WorldModel). Parameters: PerceptionParams."""

    ROLE = "perception"
    SERVICE_CLASS = "WorldModel"
    PARAMS = PerceptionParams

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.rng = random.Random(self.p.seed * 100 + self.number + (0 if self.p.side == "l" else 50))
        self.perception = PerceptionService(self.agent, "the simulator has not started")
        self.memory = Memory() if self.p.memory else None

    def on_cycle(self, world: World) -> None:
        state = observe(world, self.side, self.number, self.rng, noise=self.p.noise)
        self.perception.publish(self.memory.recall(state) if self.memory else state)


def main() -> int:
    """Entry point of ``ros2 run cf_sim_backend perception``."""
    return run(PerceptionNode)


if __name__ == "__main__":
    sys.exit(main())
