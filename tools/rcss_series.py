"""A series of matches of our team against a named opponent on rcssserver, and a table of how they went.

    python tools/rcss_series.py --server $RCSSSERVER --opponent PYRUS \\
        --opponent-cmd "bash -c 'cd /path/to/Pyrus2D && ./start.sh -t {team} --disable-file-log'" \\
        [--matches 5] [--cycles 2000] [--realtime] [--seed 0] [--out DIR] [--kick-off referee|trainer] [--no-coach]
        [--log-requests] [--talk framework|say] [--replays 1]

Each match is ``tools/rcss_match.py`` with the server's game log on (synch mode unless
--realtime; two halves; our 11 players against the opponent's, started with its own
command; match n with the server's seed SEED+n). From each
match's summary and game log (.rcg) it prints: the score, shots (kicks towards the opponent's
goal from within 25 m of it), possession (cycles of play_on in which a player of that side was
nearest the ball), time in the other's third (the share of play-on cycles in which we had the
ball, our kick its last, in their third : they in ours), tackles (hits of tries, each side), idle
at the ball (of the play-on cycles in which a field player of ours had the ball within 0.9 m, the
share in which he neither kicked nor tackled it; "held": such cycles in which his own tackle of
the last 10 cycles held him, as rcssserver's tackle_cycles does), offsides and fouls and faults (a tackle's foul, a free kick
fault, a catch outside the area, a back pass caught) called against each side, the mean top speed of each side's field players (their
heterogeneous types, m/cycle at full dashes), our CPU per cycle, relaunches, and the share of our body commands
the server executed; then the series' totals. A match the server gave up in (a client too slow
for synch mode, e.g. beside other work) is played again, up to --replays times. The opponent is never part of this repository: build it
beside it (see docs/rcssserver.md).

    python tools/rcss_series.py --again DIR   # the table of a series played into DIR, read again
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import re
import subprocess
import sys
import time
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

from proctree import run_passing_on

from cf_sim_backend.player_types import PlayerType
from cf_sim_backend.rcss.coach import player_type
from cf_sim_backend.rcss.protocol import parse

HERE = Path(__file__).resolve().parent
GOAL_X = 52.5


TACKLE_FAULT = 0x2000  # a player's state bit in the game log: his tackle this cycle missed
IDLE_REACH = 0.9  # m: a ball this close is surely kickable (the server's reach is 1.085; our skills kick one the see shows at 1.0)
TACKLE_HOLD = 10  # cycles a tackle, hit or missed, holds the tackler (rcssserver's tackle_cycles)


def read_rcg(path: Path, counters: bool = False) -> list[tuple[int, str, tuple[float, float], list[tuple]]]:
    """(time, play mode, ball, [(side, number, x, y, kicks so far)]) per show line of a game log (ULG5/6).

    ``counters``: each player also carries (tackles so far, state bits).
    """
    frames, mode = [], "before_kick_off"
    for line in path.read_text(errors="replace").splitlines():
        if line.startswith("(playmode "):
            mode = line.strip("()").split()[2]
        elif line.startswith("(show "):
            head, _, rest = line.partition(" ((b) ")
            t = int(head.split()[1])
            ball = tuple(float(v) for v in rest.split(")")[0].split()[:2])
            players = []
            for words in player_words(rest):
                side, number, x, y = words[0], int(words[1]), float(words[4]), float(words[5])
                c = words.index("c") + 1 if "c" in words else None
                kicks = int(words[c]) if c else 0
                if counters:  # (c kick dash turn catch move turn_neck change_view say tackle ...)
                    tackles = int(words[c + 8]) if c and len(words) > c + 8 else 0
                    players.append((side, number, x, y, kicks, tackles, int(words[3], 16)))
                else:
                    players.append((side, number, x, y, kicks))
            frames.append((t, mode, ball, players))
    return frames


def player_words(rest: str):
    """The words of each player's entry in a show line (``rest``: the text from the ball on):
    side, number, type, state, x, y, ...; not a player that never connected (state 0)."""
    for chunk in rest.split(" ((")[1:]:
        words = chunk.replace("(", " ").replace(")", " ").split()
        if len(words) >= 6 and words[0] in ("l", "r") and words[3] != "0":
            yield words


@dataclass(frozen=True)
class Body:
    """The ball or a player in a show line: place and velocity (m/cycle, server frame), body direction."""

    x: float
    y: float
    vx: float
    vy: float
    body: float  # degrees (a player's; the ball's is 0)


def show_bodies(line: str) -> tuple[Body, dict[tuple[str, int], Body]]:
    """The ball and the players of a game log's ``(show ...)`` line, in the server's frame."""
    _, _, rest = line.partition(" ((b) ")
    bx, by, bvx, bvy = (float(v) for v in rest.split(")")[0].split()[:4])
    players = {}
    for words in player_words(rest):
        if len(words) < 9:
            continue  # (no velocity and body: not placeable)
        x, y, vx, vy, body = (float(w) for w in words[4:9])
        players[(words[0], int(words[1]))] = Body(x, y, vx, vy, body)
    return Body(bx, by, bvx, bvy, 0.0), players


def contests(frames: list, our_side: str) -> dict:
    """Tackles of each side (hits, tries), and how often a field player of ours with the ball within
    IDLE_REACH in play on neither kicked nor tackled it (idle cycles, such cycles, idle cycles in
    which his own tackle of the last TACKLE_HOLD cycles held him) (``read_rcg(..., counters=True)``)."""
    tackles = {"l": [0, 0], "r": [0, 0]}
    idle = [0, 0, 0]
    before: dict = {}
    tackled: dict = {}  # player -> the frame of his last tackle
    for i, (_, mode, (bx, by), players) in enumerate(frames):
        now = {(p[0], p[1]): p for p in players}
        for key, (side, number, x, y, kicks, tried, state) in now.items():
            last = before.get(key)
            if last is not None and tried > last[5]:
                tackles[side][1] += 1
                tackles[side][0] += not state & TACKLE_FAULT
                tackled[key] = i  # held from this frame's cycle on
            at_ball = math.hypot(x - bx, y - by) <= IDLE_REACH
            if side == our_side and number != 1 and mode == "play_on" and at_ball and i + 1 < len(frames):
                after = next((p for p in frames[i + 1][3] if (p[0], p[1]) == key), None)
                if after is not None:
                    idle[1] += 1
                    still = after[4] == kicks and after[5] == tried
                    idle[0] += still
                    idle[2] += still and 0 <= i - tackled.get(key, -TACKLE_HOLD) < TACKLE_HOLD
        before = now
    return {"tackles": tackles, "idle": idle}


def kick_events(frames: list) -> list[tuple[int, str, int, float, float]]:
    """(frame index, side, number, x, y) of every kick in ``read_rcg``'s frames, in order."""
    events, last = [], {}
    for i, (_, _, _, players) in enumerate(frames):
        for side, number, x, y, kicks, *_ in players:
            if kicks > last.get((side, number), kicks):
                events.append((i, side, number, x, y))
            last[(side, number)] = kicks
    return events


THIRD = GOAL_X / 3  # m from the halfway line to the edge of the middle third


@dataclass
class Territory:
    held: list[int] = field(default_factory=lambda: [0, 0, 0])  # play-on cycles: our third, middle, theirs
    won: list[int] = field(default_factory=lambda: [0, 0, 0])


def third_of(x: float) -> int:
    """0, 1 or 2: the third of the field of x, counted from the goal of the side whose frame x is in."""
    return 0 if x < -THIRD else 1 if x <= THIRD else 2


def territory_of(frames: list, our_side: str) -> dict[str, Territory]:
    """Where each team ("us", "them") had the ball (its last kick was theirs) and won it back, in
    thirds seen from our goal (``read_rcg``'s frames)."""
    forward = 1.0 if our_side == "l" else -1.0
    kicked_at = {i: s for i, s, *_ in kick_events(frames)}  # the last kick of a frame decides
    out = {"us": Territory(), "them": Territory()}
    holder = None
    for i, (_, mode, ball, _) in enumerate(frames):
        third = third_of(forward * ball[0])
        kicker = kicked_at.get(i)
        if kicker is not None:
            who = "us" if kicker == our_side else "them"
            if holder is not None and who != holder and mode == "play_on":
                out[who].won[third] += 1
            holder = who
        if mode == "play_on" and holder is not None:
            out[holder].held[third] += 1
    return out


def moves_of(frames: list, our_side: str) -> list[list[int]]:
    """Our moves: for each third a move began in (our first kick after one of theirs, in play or at
    a set piece), how many got no further than each third before the opponents next kicked the
    ball (``read_rcg``'s frames; ``[begun][furthest]``, thirds counted from our goal)."""
    forward = 1.0 if our_side == "l" else -1.0
    out = [[0, 0, 0] for _ in range(3)]
    events = kick_events(frames)
    begun, holder = None, None
    for j, (i, side, *_) in enumerate(events):
        ours = side == our_side
        if ours and holder != our_side:
            begun = i
        holder = side
        ends = j + 1 == len(events) or events[j + 1][1] != our_side
        if begun is not None and ends:
            last = events[j + 1][0] if j + 1 < len(events) else len(frames) - 1
            furthest = max(forward * f[2][0] for f in frames[begun : last + 1])
            out[third_of(forward * frames[begun][2][0])][third_of(furthest)] += 1
            begun = None
    return out


FAULTS = ("foul_", "back_pass_", "free_kick_fault_", "catch_fault_", "illegal_defense_")  # X_l: by l
OFFENCES = (*FAULTS, "offside_")
TOUCH_SPEED = 1.2  # m/cycle: a kick leaving slower than this is a touch (a dribble's push, a collecting touch)


def favoured(mode: str) -> str | None:
    """The side ("l"/"r") a play mode gives the ball to, or a goal to: the side it names, but the
    other one for an offence (``foul_charge_r`` names the offender: the left side's free kick);
    None for a mode that names no side (play on, a drop ball, time up)."""
    if not mode.endswith(("_l", "_r")):
        return None
    named = mode[-1]
    return ("r" if named == "l" else "l") if mode.startswith(OFFENCES) else named


def keeping_of(frames: list, our_side: str) -> dict[tuple[str, str, str], list[int]]:
    """How each team kept the ball it kicked in play: (team "us"/"them", "own half"/"other half",
    "touch"/"kick") -> [kicks, then the kicker's own kick again, a team-mate's, an opponent's]
    (``read_rcg``'s frames). A ball out of play before the next kick counts by whom the referee
    gave it to (a throw-in, a goal kick, a goal; an offence's mode names the offender); one stopped
    otherwise (time up, a drop ball), and the match's last kick, are not counted.

    The same count for both teams, so ours can be set beside the opponent's: a base team that
    keeps its kicks where ours are lost shows what the gap is made of.
    """
    out: dict[tuple[str, str, str], list[int]] = defaultdict(lambda: [0, 0, 0, 0])
    events = kick_events(frames)
    for (i, side, number, x, _), (j, side2, number2, _, _) in itertools.pairwise(events):
        if frames[i][1] != "play_on" or i + 1 >= len(frames) or frames[i + 1][1] != "play_on":
            continue
        stop = next((frames[k][1] for k in range(i + 1, j + 1) if frames[k][1] != "play_on"), None)
        if stop is None:
            outcome = 1 if (side2, number2) == (side, number) else 2 if side2 == side else 3
        elif (given := favoured(stop)) is not None:  # out of play first: whose throw-in, goal kick, free kick or goal
            outcome = 2 if given == side else 3
        else:
            continue  # (time up, a drop ball)
        (bx, by), (ax, ay) = frames[i][2], frames[i + 1][2]
        kind = "touch" if math.hypot(ax - bx, ay - by) < TOUCH_SPEED else "kick"
        own = (x < 0) == (side == "l")
        row = out[("us" if side == our_side else "them", "own half" if own else "other half", kind)]
        row[0] += 1
        row[outcome] += 1
    return out


def newest_game_log(match: Path) -> Path | None:
    """A match directory's game log: of several, the newest finished one (the server names them by
    the time the match began, and a match it is still writing ``incomplete.rcg``); None if none."""
    return max(match.glob("*.rcg"), key=lambda p: (p.name != "incomplete.rcg", p.name), default=None)


def match_stats(rcg: Path, our_side: str) -> dict:
    """Possession, shots, tackles, offsides and faults of both sides, and our idle cycles at the ball, from a game log."""
    frames = read_rcg(rcg, counters=True)
    possession = {"l": 0, "r": 0}
    for _, mode, (bx, by), players in frames:
        if mode == "play_on" and players:
            nearest = min(players, key=lambda p: math.hypot(p[2] - bx, p[3] - by))
            if math.hypot(nearest[2] - bx, nearest[3] - by) < 3.0:
                possession[nearest[0]] += 1
    shots = shots_of(frames)
    theirs = "r" if our_side == "l" else "l"
    total = max(1, possession["l"] + possession["r"])
    calls = referee_calls(rcg)
    fights = contests(frames, our_side)
    where = territory_of(frames, our_side)
    held = max(1, sum(sum(w.held) for w in where.values()))
    return {
        "attacking": [where["us"].held[2] / held, where["them"].held[0] / held],
        "tackles": [fights["tackles"][our_side], fights["tackles"][theirs]],
        "idle": fights["idle"],
        "shots": [shots[our_side], shots[theirs]],
        "possession": [possession[our_side] / total, possession[theirs] / total],
        "offsides": [calls.get(f"offside_{our_side}", 0), calls.get(f"offside_{theirs}", 0)],
        "faults": [
            sum(n for k, n in calls.items() if k.startswith(FAULTS) and k.endswith(f"_{s}")) for s in (our_side, theirs)
        ],
        "speeds": top_speeds(rcg, our_side),
    }


def shots_of(frames: list) -> dict[str, int]:
    """Each side's shots in ``read_rcg``'s frames: its kicks from within 25 m of the goal it attacks."""
    shots = {"l": 0, "r": 0}
    for _, side, _, x, y in kick_events(frames):
        goal_x = GOAL_X if side == "l" else -GOAL_X
        if math.hypot(goal_x - x, y) < 25.0:
            shots[side] += 1
    return shots


def team_names(rcg: Path) -> tuple[str, str] | None:
    """The left and the right team's names, from the game log's first (team ...) line."""
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(team "):
            words = line.strip("()").split()
            return words[2], words[3]
    return None


def side_of(rcg: Path, team: str) -> str:
    """'l' or 'r': the side the game log's (team ...) line gives ``team``."""
    names = team_names(rcg)
    return "r" if names is not None and names[0] != team else "l"


def referee_calls(rcg: Path) -> dict[str, int]:
    """How often each play mode was called (offside_l: a left player offside; *_fault_l: a left player's fault)."""
    calls: dict[str, int] = {}
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(playmode "):
            mode = line.strip("()").split()[2]
            calls[mode] = calls.get(mode, 0) + 1
    return calls


def kick_off_types(rcg: Path) -> tuple[dict[int, PlayerType], dict[tuple[str, int], int]]:
    """The game log's player types (those it can read), and the type each player ("l"/"r", number)
    kicked off with (the first show after cycle 0)."""
    types, kick_off = {}, None
    for line in rcg.read_text(errors="replace").splitlines():
        if line.startswith("(player_type "):
            try:
                offered = player_type(parse(line))
            except ValueError:
                continue
            if offered is not None:
                types[offered.id] = offered
        elif line.startswith("(show ") and kick_off is None and int(line.split()[1]) > 0:
            kick_off = line
    played = {(s, int(n)): int(t) for s, n, t in re.findall(r"\(\((l|r) (\d+)\) (\d+)", kick_off or "")}
    return types, played


def top_speeds(rcg: Path, our_side: str) -> list[float] | None:
    """The mean top speed (m/cycle) of each side's field players at the first kick-off, ours first,
    from the game log's player types (None: the log has none)."""
    types, played = kick_off_types(rcg)
    if not types or not played:
        return None
    speeds: dict[str, list[float]] = {"l": [], "r": []}
    for (side, number), type_id in played.items():
        if number != 1 and type_id in types:  # number 1: the goalkeeper
            speeds[side].append(types[type_id].speed)
    theirs = "r" if our_side == "l" else "l"
    return [round(sum(v) / max(1, len(v)), 3) for v in (speeds[our_side], speeds[theirs])]


GAVE_UP = "Waiting too long for clients"  # rcssserver's words when a client missed 20 synch-mode cycles running


def gave_up(row: dict, out: Path) -> bool:
    """Whether a match failed because the server gave up waiting for a client in synch mode (each
    cycle 1.25 s at most, 20 such cycles in a row): a slow start beside other work (Pyrus2D's eleven
    Python players), not anything the teams did; such a match may be played again."""
    log = out / "server.log"
    return "error" in row and log.exists() and GAVE_UP in log.read_text(errors="replace")


def play_again_if_unplayed(args: argparse.Namespace, n: int, play_one=None) -> dict:
    """Match ``n`` (``play_one``: :func:`play` unless told), played again up to ``--replays`` times while
    the server gives up waiting for its clients; the row says how often it was."""
    play_one = play_one or play
    row = play_one(args, n)
    tries = 0
    while tries < args.replays and gave_up(row, Path(args.out) / f"match-{n}"):
        tries += 1  # (rcss_match sets the failed try's files aside in the match's earlier-N)
        print(f"match {n}: the server gave up waiting for its clients; playing it again", file=sys.stderr, flush=True)
        row = play_one(args, n)
    if tries:
        row["replayed"] = tries
    return row


def play(args: argparse.Namespace, n: int) -> dict:
    out = Path(args.out) / f"match-{n}"
    argv = [sys.executable, str(HERE / "rcss_match.py"), "--server", args.server, "--players", "11"]
    argv += ["--cycles", str(args.cycles), "--opponent", args.opponent, "--opponent-cmd", args.opponent_cmd]
    argv += ["--game-log", "--out", str(out), "--timeout", str(args.timeout), "--halves", "2"]
    argv += ["--seed", str(args.seed + n), "--port", str(args.port), "--kick-off", args.kick_off]
    if args.realtime:
        argv.append("--realtime")
    if args.no_coach:
        argv.append("--no-coach")
    if args.log_requests:
        argv.append("--log-requests")
    argv += ["--talk", args.talk]
    t0 = time.monotonic()
    done = run_passing_on(argv, timeout=args.timeout + 300, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        summary = json.loads(done.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        # The whole output goes to a file; the table gets the last line (the exception, as a rule).
        out.mkdir(parents=True, exist_ok=True)
        (out / "error.log").write_text(done.stdout + done.stderr)
        last = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"n": n, "error": f"exit {done.returncode}: {last} (all of it in {out / 'error.log'})"}
    players = summary.get("players", [])
    side = next((p["side"] for p in players if p.get("side")), "l")
    score = players[0]["score"] if players else [0, 0]
    ours, theirs = (score[0], score[1]) if side == "l" else (score[1], score[0])
    row = {
        "n": n,
        "score": [ours, theirs],
        "cpu_ms_per_cycle": summary.get("our_cpu_ms_per_cycle"),
        "relaunched": summary.get("relaunched", 0),
        "executed": summary.get("executed_share", 0.0),
        "seconds": round(time.monotonic() - t0),
        "side": side,
    }
    rcg = newest_game_log(out)
    if rcg is not None:
        row |= match_stats(rcg, side)
    return row


HEADER = (
    "| match | score | shots | possession | in the other's third | tackles hit/tried | idle at the ball | offsides |"
    " fouls, faults | top speed | our CPU ms/cycle | relaunches | commands executed |\n"
    "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
)


def row_line(r: dict) -> str:
    """One match's table row."""
    n = f"{r['n']} (played again)" if r.get("replayed") else r["n"]
    if "error" in r:
        return f"| {n} | failed: {r['error'][:300]} | | | | | | | | | | | |"
    shots, poss = r.get("shots", ["?", "?"]), r.get("possession", [0, 0])
    off, faults = r.get("offsides", ["?", "?"]), r.get("faults", ["?", "?"])
    (our_hit, our_try), (their_hit, their_try) = r.get("tackles", [[0, 0], [0, 0]])
    idle, at_ball, held = ([*r.get("idle", [0, 0]), None])[:3]  # (series before the held count: none)
    ours, theirs = r.get("attacking", [0, 0])
    held_text = "" if held is None else f", {held} held"
    speeds = r.get("speeds")
    speed_text = f"{speeds[0]:.2f}:{speeds[1]:.2f}" if speeds else "?"
    return (
        f"| {n} | {r['score'][0]}:{r['score'][1]} | {shots[0]}:{shots[1]} | {poss[0]:.0%}:{poss[1]:.0%} |"
        f" {ours:.0%}:{theirs:.0%} |"
        f" {our_hit}/{our_try}:{their_hit}/{their_try} | {idle / max(1, at_ball):.0%} of {at_ball}{held_text} |"
        f" {off[0]}:{off[1]} | {faults[0]}:{faults[1]} | {speed_text} | {r['cpu_ms_per_cycle']} | {r['relaunched']} |"
        f" {r['executed']:.1%} |"
    )


def totals_line(rows: list[dict]) -> str:
    played = [r for r in rows if "error" not in r]
    goals = [sum(r["score"][0] for r in played), sum(r["score"][1] for r in played)]
    won = sum(r["score"][0] > r["score"][1] for r in played)
    lost = sum(r["score"][0] < r["score"][1] for r in played)
    return f"series: {goals[0]}:{goals[1]} in {len(played)} matches; won {won}, drawn {len(played) - won - lost}, lost {lost}"


def again(out: Path, team: str) -> int:
    """The table of a series played before, its game logs read again (with this version's columns)."""
    if not (out / "series.json").exists():
        print(f"no series.json in {out}: no match of a series has ended there", file=sys.stderr)
        return 2
    rows = json.loads((out / "series.json").read_text())
    for r in rows:
        rcg = newest_game_log(out / f"match-{r['n']}")
        if "error" not in r and rcg is not None:
            r |= match_stats(rcg, r.get("side") or side_of(rcg, team))
    print(HEADER)
    for r in rows:
        print(row_line(r))
    print("\n" + totals_line(rows))
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--again", metavar="DIR", help="only print the table of the series played into DIR")
    ap.add_argument("--team", default="CF", help="our team's name in the game logs (for --again)")
    ap.add_argument("--server", help="rcssserver binary")
    ap.add_argument("--opponent", help="the opponent's team name")
    ap.add_argument("--opponent-cmd", help="its start command ({team} {host} {port} filled in)")
    ap.add_argument("--matches", type=int, default=5)
    ap.add_argument("--cycles", type=int, default=2000, help="match length (two halves)")
    ap.add_argument("--realtime", action="store_true")
    ap.add_argument("--timeout", type=float, default=3600.0, help="seconds each match may take")
    ap.add_argument(
        "--replays",
        type=int,
        default=1,
        help="times a match is played again when the server gave up waiting for a client (a slow start)",
    )
    ap.add_argument("--out", default="rcss-series")
    ap.add_argument("--seed", type=int, default=0, help="match n gets the server's player-type seed SEED+n")
    ap.add_argument(
        "--port",
        type=int,
        default=6000,
        help="the server's player port (the opponent's command gets it as {port}); a second series beside "
        "the first needs its own ROS_DOMAIN_ID, not another port (each match has a network namespace of its own)",
    )
    ap.add_argument(
        "--kick-off",
        choices=("referee", "trainer"),
        default="referee",
        help="rcss_match --kick-off: referee (heterogeneous player types, as in a competition) or trainer",
    )
    ap.add_argument("--no-coach", action="store_true", help="our team without its coach")
    ap.add_argument("--log-requests", action="store_true", help="our decisions log every new request")
    ap.add_argument(
        "--talk",
        choices=("framework", "say"),
        default="say",
        help="say (the default): our players talk only through the server's say and hear, as a competition's"
        " rules demand; framework: over the framework too",
    )
    args = ap.parse_args()
    if args.again:
        return again(Path(args.again), args.team)
    if not (args.server and args.opponent and args.opponent_cmd):
        ap.error("--server, --opponent and --opponent-cmd are needed to play a series")
    Path(args.out).mkdir(parents=True, exist_ok=True)
    print(
        f"our team v {args.opponent}: {args.matches} matches of {args.cycles} cycles, "
        f"{'real time' if args.realtime else 'synch mode'}\n"
    )
    print(HEADER)
    rows = []
    for n in range(1, args.matches + 1):
        rows.append(play_again_if_unplayed(args, n))
        print(row_line(rows[-1]), flush=True)
        (Path(args.out) / "series.json").write_text(json.dumps(rows, indent=1))  # after each match: --again
    print("\n" + totals_line(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
