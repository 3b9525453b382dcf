"""How far off an opponent out of sight is believed some cycles after he was last seen: kept where he
was seen, or run on as the belief has it (``rcss.belief.run_on``), against the game log's truth.

    python tools/rcss_run_on.py MATCH_DIR [MATCH_DIR ...] [--team CF] [--cycles 2 4 7 10 15] [--near 5 25]

For every play-on cycle t and every field player of the other team who is ``--near`` metres from
the ball k cycles later (the men a pass or a carry has to get past): where he truly is at t+k,
against where he was at t (kept) and where ``run_on`` takes him from his place and velocity at t
(the velocity the game log shows is the one a see shows: after the cycle's decay). Per k, the
median error and the share more than 3 m off. No see noise: it comes on top of both.
"""

from __future__ import annotations

import math
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_ball_use import game_log, match_parser
from rcss_series import Body, show_bodies, side_of

from cf_sim_backend.rcss.belief import run_on

OFF = 3.0  # m: further off than this, the man is as good as unknown to a pass judged on him


def moving_frames(rcg: Path) -> dict[int, tuple[Body, dict[tuple[str, int], Body]]]:
    """Play-on time -> the ball and the players of a game log's show line."""
    frames, mode = {}, "before_kick_off"
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(playmode "):
            mode = line.strip("()").split()[2]
        elif line.startswith("(show ") and mode == "play_on":
            frames[int(line.split()[1])] = show_bodies(line)
    return frames


def errors(match: Path, team: str, cycles: list[int], near: tuple[float, float]) -> dict[int, list[tuple]]:
    """k -> [(kept error, run-on error)] for the other team's field players ``near`` the ball at t+k."""
    rcg = game_log(match)
    ours = side_of(rcg, team)
    frames = moving_frames(rcg)
    out: dict[int, list[tuple]] = {k: [] for k in cycles}
    for t, (_, players) in frames.items():
        for k in cycles:
            later = frames.get(t + k)
            if later is None:
                continue
            ball, now = later
            for key, b in players.items():
                if key[0] == ours or key[1] == 1 or key not in now:
                    continue
                truth = (now[key].x, now[key].y)
                if not near[0] <= math.dist(truth, (ball.x, ball.y)) <= near[1]:
                    continue
                rx, ry, _, _ = run_on(b.x, b.y, b.vx, b.vy, k)
                out[k].append((math.dist((b.x, b.y), truth), math.dist((rx, ry), truth)))
    return out


def table(rows: dict[int, list[tuple]]) -> str:
    lines = [
        f"| cycles unseen | men | kept where seen: median off (m) | more than {OFF:g} m off | run on: median off (m) | more than {OFF:g} m off |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    for k, pairs in rows.items():
        if not pairs:
            continue
        kept, ran = zip(*pairs, strict=True)
        share = [sum(e > OFF for e in es) / len(es) for es in (kept, ran)]
        lines.append(
            f"| {k} | {len(pairs)} | {statistics.median(kept):.2f} | {share[0]:.0%} "
            f"| {statistics.median(ran):.2f} | {share[1]:.0%} |"
        )
    return "\n".join(lines)


def main() -> int:
    ap = match_parser(__doc__)
    ap.add_argument("--cycles", type=int, nargs="+", default=[2, 4, 7, 10, 15], help="cycles since last seen")
    ap.add_argument("--near", type=float, nargs=2, default=[5.0, 25.0], help="m from the ball: the men counted")
    args = ap.parse_args()
    total: dict[int, list[tuple]] = {k: [] for k in args.cycles}
    for match in args.matches:
        for k, pairs in errors(match, args.team, args.cycles, tuple(args.near)).items():
            total[k] += pairs
    print(table(total))
    return 0


if __name__ == "__main__":
    sys.exit(main())
