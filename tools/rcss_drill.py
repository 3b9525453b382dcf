"""Drills on a real rcssserver: the same situation of ours again and again against a named opponent,
and what came of each try.

    python tools/rcss_drill.py --server $RCSSSERVER --opponent HELIOS_base --opponent-cmd "start.sh -t {team}"
                               [--drill kick-off|free-kick|replay] [--at X Y] [--tries 30] [--window 100] [--out DIR]
                               [--from MATCH_DIR ...] [--zone X0 X1] [--list]
                               (and any option of tools/rcss_match.py)

A match gives our team five or six kick-offs in 2000 cycles; a drill gives one every ~110 cycles.
The trainer (rcssserver's offline coach) sets each try up: it calls ``before_kick_off`` (both teams
take their kick-off places), gives every player his stamina back (``recover``), puts the ball on
the centre spot (a kick-off) or at ``--at X Y`` (a free kick of ours, in our decision's frame: X up
the field towards their goal, Y to the left of that), and gives us the kick-off or the free kick.
The try ends ``--window`` cycles after our first kick, at a goal, or when the referee stops play
for the other side; then the next is set up.

``--drill replay`` sets up open play instead: situations of earlier matches' game logs (``--from``,
match directories), each the moment before a kick of ours in play with the ball in ``--zone``
(metres up the field in our frame; their half by default), at least GAP cycles after the last one
taken. The trainer puts all 22 players (their body's direction too) and the ball where that game
log had them, holds them there for HOLD steps (both sides see the picture and believe it) and
lets them go with the game log's velocities, in play on. The tries go through the situations in
order, evenly spread over them when there are more than tries. The opponent should be the one of
those matches (its players are placed by shirt number). ``--list`` prints how many such moments
each game log holds and stops (no server): how often we had the ball that far up, before a drill.
Synch mode only (the trainer counts the server's steps). The first try is the referee's own
kick-off, so heterogeneous player types are handed out as in a match.

The server's game log is read afterwards; per try: our kick taken, the furthest the ball got up
the field before their first kick, the cycles until that kick, our shots (kicks from within 25 m
of their goal, as ``rcss_series`` counts them), the balls we won back in their third (in play, as
``rcss_series`` counts them) and the goals.
The table and ``drill.json`` (in --out) are the result.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rcss_match import Trainer, kick_off, launch, parser
from rcss_series import (
    THIRD,
    Body,
    favoured,
    kick_events,
    newest_game_log,
    read_rcg,
    shots_of,
    show_bodies,
    side_of,
    territory_of,
)

MODES = {"kick-off": "kick_off", "free-kick": "free_kick", "replay": "play_on"}  # the drill -> the play mode it sets
SETTLE = 10  # steps in before_kick_off for both teams to take their places
STEP_WAIT = 30.0  # s without a simulation step: the server is stuck or gone
TAKE_WAIT = 100  # steps our taker has to kick before the try is given up
HOLD = 4  # steps a replayed situation is held still before play goes on
GAP = 30  # cycles between two situations taken from one game log


@dataclass(frozen=True)
class Situation:
    """A moment of an earlier match in the server's frame, turned round if need be so that we are
    the left side (as in a drill)."""

    source: str  # the game log's name and time, for the record
    ball: Body
    ours: dict[int, Body]
    theirs: dict[int, Body]


def as_left(b: Body, our_side: str) -> Body:
    """``b`` turned round the centre spot when we played on the right."""
    if our_side == "l":
        return b
    return Body(-b.x, -b.y, -b.vx, -b.vy, math.remainder(b.body + 180.0, 360.0))


def situations(rcg: Path, team: str, zone: tuple[float, float], gap: int = GAP) -> list[Situation]:
    """The moments before kicks of ours in play with the ball within ``zone`` (x, our frame), each at
    least ``gap`` cycles after the last one taken, in ``rcg`` (where ``team`` played either side)."""
    side = side_of(rcg, team)
    forward = 1.0 if side == "l" else -1.0
    frames = read_rcg(rcg)
    chosen, last = [], None
    for i, kicker, *_ in kick_events(frames):
        t, mode, ball, _ = frames[i - 1]  # (kick_events finds a kick from the second frame on)
        if kicker != side or mode != "play_on" or not zone[0] <= forward * ball[0] <= zone[1]:
            continue
        if last is None or t - last >= gap:
            chosen.append(t)
            last = t
    shows = {}
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(show "):
            t = int(line.split()[1])
            if t in chosen and t not in shows:  # (a stopped clock repeats a time: its first show)
                shows[t] = line
    out = []
    for t in chosen:
        ball, players = show_bodies(shows[t])
        ours = {n: as_left(b, side) for (s, n), b in players.items() if s == side}
        theirs = {n: as_left(b, side) for (s, n), b in players.items() if s != side}
        out.append(Situation(f"{rcg.name}@{t}", as_left(ball, side), ours, theirs))
    return out


def spread(items: list, n: int) -> list:
    """``n`` of ``items`` evenly spread over them, in order (all of them, over again, when too few)."""
    if len(items) >= n:
        return [items[i * len(items) // n] for i in range(n)]
    return [items[i % len(items)] for i in range(n)]


def placement(s: Situation, team: str, opponent: str, moving: bool) -> list[str]:
    """The trainer's commands that put everyone where ``s`` has them; ``moving``: with the game log's
    velocities, else standing still."""

    def move(who: str, b: Body, turn: bool = True) -> str:
        v = f" {b.vx:g} {b.vy:g}" if moving else " 0 0"
        return f"(move {who} {b.x:g} {b.y:g} {b.body if turn else 0:g}{v})"  # (the ball's angle is read, unused)

    ours = [move(f"(player {team} {n})", b) for n, b in sorted(s.ours.items())]
    theirs = [move(f"(player {opponent} {n})", b) for n, b in sorted(s.theirs.items())]
    return [*ours, *theirs, move("(ball)", s.ball, turn=False)]


@dataclass(frozen=True)
class Try:
    start: int  # the game time our set piece began
    taken: bool  # we kicked the ball
    furthest: float  # m up the field (our frame) the ball got before their first kick (set piece spot if none)
    kept: int  # cycles from our first kick to theirs (the window's end if none)
    shots: int  # our kicks from within 25 m of their goal (rcss_series.shots_of)
    won_there: int  # balls we won in their third in play (rcss_series.territory_of, as a series counts them)
    goals_for: int
    goals_against: int


def tries_of(frames: list, our_side: str, set_piece: str, starts: list[int]) -> list[Try]:
    """The tries in ``read_rcg``'s frames: each from our ``set_piece`` (e.g. ``kick_off``) at or after
    a game time in ``starts`` (when the trainer gave it) to the next try's (the game log does not
    show the trainer's ``before_kick_off``, and the clock stands still in it)."""
    fwd = 1.0 if our_side == "l" else -1.0
    ours = set_piece if set_piece == "play_on" else f"{set_piece}_{our_side}"
    begins = [next((i for i, f in enumerate(frames) if f[0] >= t and f[1] == ours), None) for t in starts]
    begins = [i for i in begins if i is not None]
    out = []
    for n, begin in enumerate(begins):
        seg = frames[begin : begins[n + 1] if n + 1 < len(begins) else len(frames)]
        kicks = kick_events(seg)
        first_ours = next((e for e in kicks if e[1] == our_side), None)
        first_theirs = next(
            (e for e in kicks if e[1] != our_side and (first_ours is None or e[0] > first_ours[0])), None
        )
        upto = first_theirs[0] if first_theirs is not None else len(seg) - 1
        furthest = max(fwd * f[2][0] for f in seg[: upto + 1])
        kept = 0
        if first_ours is not None:
            kept = seg[upto][0] - seg[first_ours[0]][0]
        modes = {f[1] for f in seg}
        them = "r" if our_side == "l" else "l"
        out.append(
            Try(
                start=seg[0][0],
                taken=first_ours is not None,
                furthest=round(furthest, 1),
                kept=kept,
                shots=shots_of(seg)[our_side],
                won_there=territory_of(seg, our_side)["us"].won[2],
                goals_for=int(f"goal_{our_side}" in modes),
                goals_against=int(f"goal_{them}" in modes),
            )
        )
    return out


def table(tries: list[Try], title: str) -> str:
    """One row for the drill: counts over the tries taken, medians of how far and how long."""
    taken = [t for t in tries if t.taken]
    if not taken:
        return f"{title}: no try taken of {len(tries)}"
    far = [t.furthest for t in taken]
    rows = [
        f"{title}: {len(taken)} tries taken of {len(tries)}",
        "",
        "| goals | tries with a shot | shots | into their third | beyond 30 m | furthest (median)"
        " | kept, cycles (median) | won in their third |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|",
        f"| {sum(t.goals_for for t in taken)}:{sum(t.goals_against for t in taken)}"
        f" | {sum(t.shots > 0 for t in taken)} | {sum(t.shots for t in taken)}"
        f" | {sum(f > THIRD for f in far)} | {sum(f > 30.0 for f in far)}"
        f" | {statistics.median(far):.1f} m | {statistics.median(t.kept for t in taken):.0f}"
        f" | {sum(t.won_there for t in taken)} |",
    ]
    return "\n".join(rows)


def set_up(trainer: Trainer, args: argparse.Namespace, situation: Situation | None = None) -> None:
    """Both teams to their kick-off places, stamina back, the ball placed, our set piece given; or
    everyone where ``situation`` has them, held still for HOLD steps, then play on."""
    if situation is not None:
        # Through another mode first: rcssserver's referee forgets the last set piece's taker on any
        # change of mode but to play_on, and a kick-off taker placed at the ball who kicked it again
        # was called for a free kick fault.
        trainer.send("(change_mode before_kick_off)")
        trainer.send("(change_mode play_on)")
        trainer.send("(recover)")
        for _ in range(HOLD):
            for command in placement(situation, args.team, args.opponent, moving=False):
                trainer.send(command)
            wait_steps(trainer, 1)
        for command in placement(situation, args.team, args.opponent, moving=True):
            trainer.send(command)
        return
    trainer.send("(change_mode before_kick_off)")
    wait_steps(trainer, SETTLE)
    trainer.send("(recover)")
    x, y = args.at if args.drill == "free-kick" else (0.0, 0.0)
    trainer.send(f"(move (ball) {x} {-y} 0 0 0)")  # we are the left side; the server's y runs the other way
    trainer.send(f"(change_mode {MODES[args.drill]}_l)")


def wait_steps(trainer: Trainer, steps: int, until=lambda: False) -> None:
    """Answer the server for ``steps`` simulation steps, or until ``until()``."""
    end, stuck = trainer.thinks + steps, time.monotonic() + STEP_WAIT
    while trainer.thinks < end and not until():
        seen = trainer.thinks
        trainer.poll()
        if trainer.thinks > seen:
            stuck = time.monotonic() + STEP_WAIT
        elif time.monotonic() > stuck:
            raise RuntimeError(f"the server sent no step for {STEP_WAIT} s (at game time {trainer.time})")


def drill(args: argparse.Namespace, trainer: Trainer, server, team_procs: list, summary: dict) -> None:
    """Play ``args.tries`` tries, one after the other, then call time over."""
    trainer.send("(eye on)")  # the server sends the trainer (think) only with its eye on, and then waits for it
    kick_off(args, trainer)  # the referee's, as a match's: heterogeneous types handed out; the first kick-off try
    started, set_piece = time.monotonic(), f"{MODES[args.drill]}_l"
    summary["starts"] = starts = []  # the game time of each try's set piece
    for n in range(args.tries):
        if n > 0 or args.drill != "kick-off":
            if n == 0:  # straight from the referee's kick-off to the first free kick
                wait_steps(trainer, 2)
            set_up(trainer, args, args.situations[n] if args.situations else None)
        starts.append(trainer.time)  # (the clock stood still in before_kick_off: the set piece's time)
        wait_steps(trainer, 3)
        if not args.situations:
            wait_steps(trainer, TAKE_WAIT, lambda: trainer.mode != set_piece)
        wait_steps(trainer, args.window, lambda: trainer.mode.startswith("goal_") or ended_for_them(trainer.mode))
        wait_steps(trainer, 2)  # the goal or the stop into the game log
        if server.poll() is not None:
            raise RuntimeError(f"rcssserver exited with {server.returncode}: see {summary['out']}/server.log")
        if time.monotonic() - started > args.timeout:
            raise RuntimeError(f"the drill did not end in {args.timeout} s (try {n + 1})")
    trainer.send("(eye off)")  # the server no longer waits for us
    trainer.send("(change_mode time_over)")
    summary["seconds"] = round(time.monotonic() - started, 1)


def ended_for_them(mode: str) -> bool:
    """The referee stopped play and gave the ball to the other side (we are the left team): a mode
    of theirs, or an offence of ours (the mode names the offender: ``foul_charge_r`` is our free kick)."""
    goal = mode.startswith("goal_") and not mode.startswith("goal_kick_")  # (a goal ends a try by itself)
    return favoured(mode) == "r" and not goal


def main() -> int:
    ap = parser(__doc__.split("\n\n")[0])
    ap.add_argument("--drill", choices=tuple(MODES), default="kick-off")
    ap.add_argument("--at", type=float, nargs=2, default=(30.0, -20.0), metavar=("X", "Y"), help="free kick spot")
    ap.add_argument("--tries", type=int, default=30)
    ap.add_argument("--window", type=int, default=100, help="cycles a try runs after our first kick")
    ap.add_argument("--from", dest="sources", nargs="+", default=[], metavar="MATCH_DIR", help="replay: game logs")
    ap.add_argument(
        "--zone", type=float, nargs=2, default=(0.0, 52.5), metavar=("X0", "X1"), help="replay: the ball's x"
    )
    ap.add_argument("--list", action="store_true", help="replay: count the moments per game log and stop")
    ap.set_defaults(timeout=3600.0, game_log=True)
    args = ap.parse_args()
    if args.realtime:
        ap.error("drills run in synch mode")
    if args.tries < 1 or args.window < 1:
        ap.error("--tries and --window must be positive")
    if args.list and args.drill != "replay":
        ap.error("--list counts a replay drill's moments: give it with --drill replay")
    args.game_log, args.halves, args.kick_off = True, 1, "referee"
    args.situations = []
    if args.drill == "replay":
        if not args.sources or args.zone[0] >= args.zone[1]:
            ap.error("--drill replay needs --from MATCH_DIR ... and a --zone X0 X1 with X0 < X1")
        found, held = [], 0
        for source in args.sources:
            rcg = newest_game_log(Path(source))
            if rcg is None:
                ap.error(f"no game log in {source}")
            here = situations(rcg, args.team, tuple(args.zone))
            found += here
            held += bool(here)
            if args.list:
                print(f"{source}: {len(here)}")
        if args.list:
            zone = f"{args.zone[0]:g}..{args.zone[1]:g}"
            print(f"{len(found)} moments with the ball at x {zone} in {len(args.sources)} game logs, {held} with any")
            return 0
        if not found:
            ap.error(f"no kick of {args.team}'s in play with the ball in x {args.zone[0]:g}..{args.zone[1]:g} (--from)")
        args.situations = spread(found, args.tries)
    args.cycles = 10 * (args.tries * (args.window + TAKE_WAIT) // 10 + 100)  # no half time within the drill

    def report(summary: dict) -> None:
        out = Path(summary["out"])
        rcg = newest_game_log(out)
        if rcg is None:
            raise RuntimeError(f"no game log in {out}")
        side = side_of(rcg, args.team)
        tries = tries_of(read_rcg(rcg), side, MODES[args.drill], summary["starts"])
        where = {"kick-off": "", "free-kick": f" at ({args.at[0]:g}, {args.at[1]:g})"}.get(
            args.drill, f" of {len({s.source for s in args.situations})} situations"
        )
        print(table(tries, f"our {args.drill}{where} against {args.opponent}"), flush=True)
        result = {"drill": args.drill, "at": list(args.at), "tries": [asdict(t) for t in tries], **summary}
        result["situations"] = [s.source for s in args.situations]
        result.pop("players", None)
        (out / "drill.json").write_text(json.dumps(result, indent=1))

    return launch(ap, args, drill, report)


if __name__ == "__main__":
    sys.exit(main())
