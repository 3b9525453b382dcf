"""How far off our players' picture of the ball was, against the game log's truth, by its distance;
and how far off their picture of the opponents' offside line, and how near it the forwards sent
there stood.

    python tools/rcss_belief_error.py MATCH_DIR [MATCH_DIR ...] [--team CF]

A MATCH_DIR is what ``tools/rcss_match.py --game-log --log-requests --out DIR`` writes
(``rcss_series``: its ``match-N``). Each new request a decision logs (``request t=T ... | me X Y |
ball X Y v VX VY age A | line X``) says where the player believed himself and the ball, how fast he
believed it rolled and where he believed their offside line; the game log says where they were.
Counted for the ball: balls seen that cycle (age 0) that were rolling (BALL_MOVING or faster). One
row per band of the believed distance from the player. The embedded simulator's perception noise
is set from this table (docs/simulator.md).

The line (a second table, requests in play on): the believed line against the true one (the
second-last opponent's x, or the ball's if further up, never short of the halfway line, as
``cf_decision.situation.offside_line`` takes it); and for every cycle in play on in which a
player's request in force (his last one logged) had the reason ON_LINE, his true x short of the
true line (negative: beyond it, offside).
"""

from __future__ import annotations

import itertools
import math
import re
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game, game_log, logged, match_parser
from rcss_options import offside_x
from rcss_series import side_of

from cf_decision import reach

BALL_MOVING = 0.05  # m/cycle
ON_LINE = "forward: on their last line"  # the decision's reason for a forward sent to their line
BANDS = ((0.0, 2.0), (2.0, 5.0), (5.0, 10.0), (10.0, 20.0), (20.0, 40.0), (40.0, 200.0))  # metres
_NUM = r"(-?[\d.]+)"
_REQUEST = re.compile(
    rf"\[(\w+)_(\d+)_decision\]: request t=(\d+) .*?\| me {_NUM} {_NUM} \| ball {_NUM} {_NUM} v {_NUM} {_NUM} age (\d+)"
)

_WHY = re.compile(r"\[(\w+)_(\d+)_decision\]: request t=(\d+) \w+: ([^|]*?)(?:, watch the ball)? \|")
_LINE = re.compile(rf" \| line {_NUM} \| ")


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
    for m in logged(match, team, _REQUEST, balls):
        me_x, me_y, x, y, vx, vy = (float(m.group(i)) for i in range(4, 10))
        tx, ty, tvx, tvy = balls[int(m.group(3))]
        if int(m.group(10)) != 0 or math.hypot(tvx, tvy) < BALL_MOVING:
            continue
        out.append(
            Error(math.hypot(x - me_x, y - me_y), math.hypot(x - tx, y - ty), math.hypot(vx / 10 - tvx, vy / 10 - tvy))
        )
    return out


@dataclass(frozen=True)
class LineError:
    believed: float  # m: the offside line's x as the player believed it (his frame)
    true: float  # m: the true one


def true_lines(match: Path, team: str) -> dict[int, tuple[float, dict[int, float]]]:
    """Cycle in play on -> their offside line (``rcss_options.offside_x``) and our players' x, in our
    frame (the first show line of each cycle)."""
    frames, side, forward = game(match, team)
    out: dict[int, tuple[float, dict[int, float]]] = {}
    for t, mode, (bx, by), players in frames:
        if mode != "play_on" or t in out:
            continue
        theirs = [reach.Runner((forward * p[2], forward * p[3])) for p in players if p[0] != side]
        line = offside_x((forward * bx, forward * by), theirs)
        if line is not None:
            out[t] = (line, {p[1]: forward * p[2] for p in players if p[0] == side})
    return out


def line_errors(match: Path, team: str = "CF") -> tuple[list[LineError], list[float]]:
    """In one match: every request of ``team``'s decisions in play on that told a line; and for each
    cycle in play on while a player's request in force was ON_LINE, his true x short of the true line."""
    lines = true_lines(match, team)
    found, whys = [], {}
    for m in logged(match, team, _WHY):
        t, number = int(m.group(3)), int(m.group(2))
        whys.setdefault(number, []).append((t, m.group(4)))
        told = _LINE.search(m.string)
        if told and t in lines:
            found.append(LineError(float(told.group(1)), lines[t][0]))
    short = []
    for number, said in whys.items():
        said = sorted(said, key=lambda request: request[0])  # (a relaunched player's lines may come later)
        for (since, why), (until, _) in itertools.pairwise([*said, (max(lines, default=0) + 1, "")]):
            if why == ON_LINE:
                in_play = (lines[t] for t in range(since, until) if t in lines)
                short += [line - ours[number] for line, ours in in_play if number in ours]
    return found, short


def line_table(found: list[LineError], short: list[float]) -> list[str]:
    """The markdown rows: the believed line's error, and how far short of it the forwards sent there stood."""
    off = sorted(abs(e.believed - e.true) for e in found)
    short = sorted(short)
    rows = [
        "| their line: requests | off, median (m) | 90% within | cycles a forward was sent to it "
        "| he stood short of it: median (m) | quartiles |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    if not off:
        return rows
    quartiles = f"{short[len(short) // 4]:.1f} to {short[(3 * len(short)) // 4]:.1f}" if short else "-"
    middle = f"{statistics.median(short):.1f}" if short else "-"
    rows.append(
        f"| {len(off)} | {statistics.median(off):.2f} | {off[int(0.9 * (len(off) - 1))]:.2f} | {len(short)} "
        f"| {middle} | {quartiles} |"
    )
    return rows


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
    believed, short = [], []
    for match in args.matches:
        found_here, short_here = line_errors(match, args.team)
        believed.extend(found_here)
        short.extend(short_here)
    if believed:  # (request logs from before the line was logged have none)
        print("\n" + "\n".join(line_table(believed, short)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
