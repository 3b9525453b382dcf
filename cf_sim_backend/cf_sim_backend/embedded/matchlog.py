"""The match log: every cycle's true state, one JSON object per line (format in docs/simulator.md)."""

from __future__ import annotations

import json
from pathlib import Path

from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.world import Side

FORMAT = "cf-match-log"
VERSION = 1


class MatchLog:
    def __init__(self, path: Path, sim: Simulator, cycle_period: float):
        path.parent.mkdir(parents=True, exist_ok=True)
        self._file = open(path, "w", encoding="utf-8", buffering=1)  # noqa: SIM115 - lives as long as the match
        prm = sim.world.params
        self._sim = sim
        self._write(
            {
                "format": FORMAT,
                "version": VERSION,
                "field": {"length": prm.field_length, "width": prm.field_width, "goal_width": prm.goal_width},
                "teams": {"l": sim.world.team_names[Side.LEFT], "r": sim.world.team_names[Side.RIGHT]},
                "cycle_seconds": cycle_period,
            }
        )

    def _write(self, obj: dict) -> None:
        self._file.write(json.dumps(obj, separators=(",", ":")) + "\n")

    def cycle(self, snapshot: dict, events: list[str]) -> None:
        line = {**snapshot, "counts": self._sim.counts()}
        if events:
            line["events"] = events
        self._write(line)

    def close(self, extra: dict | None = None) -> None:
        stats = {k: {s.value: v for s, v in d.items()} for k, d in self._sim.stats.items()}
        w = self._sim.world
        self._write({"end": True, "score": [w.score[Side.LEFT], w.score[Side.RIGHT]], "stats": stats, **(extra or {})})
        self._file.close()
