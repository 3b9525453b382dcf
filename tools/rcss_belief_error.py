"""How far off our players' picture of the ball was, against the game log's truth, by its distance.

    python tools/rcss_belief_error.py MATCH_DIR [MATCH_DIR ...] [--team CF]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --log-requests --out DIR`` writes
(``rcss_series``: its ``match-N``). Each new request a decision logs (``request t=T ... | me X Y |
ball X Y v VX VY age A``) says where the player believed himself and the ball and how fast he
believed it rolled; the game log says where it was. Counted: balls seen that cycle (age 0) that
were rolling (BALL_MOVING or faster). One row per band of the believed distance from the player.
The embedded simulator's perception noise is set from this table (docs/simulator.md).
"""

from __future__ import annotations

import math
import re
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game_log, match_parser
from rcss_series import side_of

BALL_MOVING = 0.05  # m/cycle
BANDS = ((0.0, 2.0), (2.0, 5.0), (5.0, 10.0), (10.0, 20.0), (20.0, 40.0), (40.0, 200.0))  # metres
_NUM = r"(-?[\d.]+)"
_REQUEST = re.compile(
    rf"\[(\w+)_(\d+)_decision\]: request t=(\d+) .*?\| me {_NUM} {_NUM} \| ball {_NUM} {_NUM} v {_NUM} {_NUM} age (\d+)"
)


@dataclass(frozen=True)
class Error:
    distance: float  # m: the ball from the player, as he believed
    position: float  # m: the believed ball from the true one
    velocity: float  # m/cycle: the believed velocity from the true one


def truth(rcg: Path, side: str) -> dict[int, tuple[float, float, float, float]]:
    """Cycle -> the ball's place and velocity (m/cycle) in our side's own frame (x towards their goal)."""
    sign = 1.0 if side == "l" else -1.0  # rcssserver's frame mirrors y; the right side's turns round
    out = {}
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(show "):
            x, y, vx, vy = (float(v) for v in line.split("((b) ", 1)[1].split(")", 1)[0].split()[:4])
            out[int(line.split()[1])] = (sign * x, -sign * y, sign * vx, -sign * vy)
    return out


def errors(match: Path, team: str = "CF") -> list[Error]:
    """Every counted request of ``team``'s decisions in one match."""
    rcg = game_log(match)
    balls = truth(rcg, side_of(rcg, team))
    out = []
    for log in sorted(match.glob(f"logs-{team}/*.log")):
        for line in log.read_text(errors="replace").splitlines():
            m = _REQUEST.search(line)
            if not m or m.group(1) != team or int(m.group(10)) != 0 or int(m.group(3)) not in balls:
                continue
            me_x, me_y, x, y, vx, vy = (float(m.group(i)) for i in range(4, 10))
            tx, ty, tvx, tvy = balls[int(m.group(3))]
            if math.hypot(tvx, tvy) < BALL_MOVING:
                continue
            out.append(
                Error(
                    math.hypot(x - me_x, y - me_y), math.hypot(x - tx, y - ty), math.hypot(vx / 10 - tvx, vy / 10 - tvy)
                )
            )
    return out


def table(found: list[Error]) -> list[str]:
    """The markdown rows: medians and 90th percentiles by band of distance."""
    rows = [
        "| ball's distance | requests | place off, median (m) | velocity off, median (m/cycle) | 90% within |",
        "|---|---:|---:|---:|---:|",
    ]
    for low, high in BANDS:
        band = sorted(e.velocity for e in found if low <= e.distance < high)
        if not band:
            continue
        place = statistics.median(e.position for e in found if low <= e.distance < high)
        rows.append(
            f"| {low:.0f}-{high:.0f} m | {len(band)} | {place:.2f} | {statistics.median(band):.3f} "
            f"| {band[int(0.9 * (len(band) - 1))]:.3f} |"
        )
    return rows


def main() -> int:
    args = match_parser(__doc__).parse_args()
    found = [e for match in args.matches for e in errors(match, args.team)]
    if not found:
        print("no request lines with a ball seen (was the match played with --log-requests?)")
        return 1
    print("\n".join(table(found)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
