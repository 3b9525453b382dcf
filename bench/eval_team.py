"""Evaluation: the cf_decision team against the naive team (every player chases the ball).

Plays seeded matches on the simulator core, in-process and without ROS, but through the same
pieces the nodes use: each cf_decision player perceives with `perception.observe` (view cone,
noise), decides with `cf_decision.policy.decide` and acts through `skills.skill_for`; team-mates
share their times to the ball, the passes they ask for and what they see (``shared.py``) as the
decision components do over ACL (a pass is heard in the next cycle, a sighting in the same);
with ``--talk say`` they only say their passes through the simulator's say and hear, and judge
who goes for the ball from where they see each other (``cf_decision/talk.py``).

    python bench/eval_team.py [--matches 10] [--players 11] [--half-cycles 1500] [--opponent chasers|ours]
                              [--out DIR] [--player-types 18] [--talk framework|say]

Each match's seed also draws rcssserver 19's heterogeneous player types (``player_types.py``),
which both sides get by our coach's rule; ``--player-types 1`` plays with the default type only.

``--opponent ours`` plays the cf_decision team against itself. ``--out DIR`` keeps each match as
``DIR/match-SEED/``: the match log, its game log (``.rcg``, with rcssserver's command counters)
and each player's decision log (``logs-CF/``, the lines a decision component logs), the layout
``tools/rcss_match.py --out`` writes, so the rcssserver analysis tools (``tools/rcss_ball_use.py``,
``rcss_goals.py``, ``rcss_series.py``'s counts) read a match of either back-end.
"""

from __future__ import annotations

import argparse
import random
import statistics
from pathlib import Path

from cf_decision.policy import decide
from cf_decision.receive import Announced, to_announce
from cf_decision.requests import choice_text, same_request
from cf_decision.set_piece import KICKING, SetPieceTaker
from cf_decision.shared import merged, to_tell, told_to
from cf_decision.situation import offside_mates
from cf_decision.talk import NOT_ME, Listener, pass_word, seen_claims
from cf_decision.touch import LastTouch
from cf_decision.without_ball import NEVER, state_eta
from cf_lang.ontology import Team
from cf_sim_backend.embedded.chaser import chase_commands
from cf_sim_backend.embedded.matchlog import MatchLog
from cf_sim_backend.embedded.rcg import export
from cf_sim_backend.embedded.sim import Simulator
from cf_sim_backend.memory import Memory
from cf_sim_backend.perception import observe
from cf_sim_backend.skills import SkillError, skill_for
from cf_sim_backend.world import Params, Side


class PolicyTeam:
    """Drives one side with the cf_decision policy, one skill per player at a time."""

    def __init__(self, sim: Simulator, side: Side, seed: int, log_dir: Path | None = None, talk: str = "framework"):
        self.sim, self.side = sim, side
        self.says = talk == "say"
        self.rng = random.Random(seed)
        self.current: dict[int, tuple[tuple, object]] = {}
        self.takers: dict[int, SetPieceTaker] = {}
        self.touches: dict[int, LastTouch] = {}
        self.team = sim.world.team_names[side]
        self.logs: dict[int, list[str]] = {}  # number -> the decision component's log lines
        self.log_dir = log_dir
        self.memories: dict[int, Memory] = {}  # number -> what he remembers (as the perception component)
        self.passes: dict[int, dict[int, Announced]] = {}  # hearer -> passer -> the pass he heard
        self.listeners: dict[int, Listener] = {}  # hearer -> what he heard said (--talk say)
        self.size = sum(1 for p in sim.world.players.values() if p.side is side)

    def commands(self) -> None:
        w = self.sim.world
        states = {
            p.number: self.memories.setdefault(p.number, Memory(w.params)).recall(
                observe(w, self.side, p.number, self.rng)
            )
            for p in w.players.values()
            if p.side is self.side
        }
        claims, may_touch = {}, {}
        for n, st in states.items():
            touch = self.touches.setdefault(n, LastTouch())
            touch.seen(st)  # (the decision node sees the state merged with team-mates' words)
            may_touch[n] = self.takers.setdefault(n, SetPieceTaker()).may_touch(st) and not touch.offside(st.time)
            eta = state_eta(st)
            if eta is not None:
                claims[n] = eta if may_touch[n] else NEVER
        words = {n: None if self.says else to_tell(st) for n, st in states.items()}
        near = set() if self.says else told_to(claims)  # (the team-mates a word goes to)
        asked = []
        for n, st in states.items():
            if self.says:
                self._read_says(n, st)
            if n in near:
                st, _ = merged(st, [word for m, word in words.items() if m != n and word is not None])
            me = w.player(self.side, n)
            mine = w.as_player(me)  # the skills read my type's parameters
            mate_touched = self.touches[n].team is Team.OUR
            heard = list(self.passes.get(n, {}).values())
            if self.says:
                told = seen_claims(st, n, self.listeners[n].not_theirs(st.time))
                if not may_touch[n]:
                    self.sim.command(self.side, n, "say", NOT_ME)
            else:
                told = claims
            decision = decide(st, n, self.size, told, may_touch[n], heard, mate_touched)
            self.takers[n].decided(st, decision)
            if to_announce(st, decision):
                asked.append((n, decision.action))
                if self.says:
                    self.sim.command(self.side, n, "say", pass_word(decision.action))
            key = (decision.method, decision.action)
            current = self.current.get(n)
            if current is None or not same_request(current[0], key):
                if decision.method in KICKING:  # as the decision component logs a new way of playing the ball
                    self.logs.setdefault(n, []).append(f"[{self.team}_{n}_decision]: {choice_text(st, decision)}")
                try:
                    skill = skill_for(decision.method, decision.action, self.side, mine, me)
                except SkillError:
                    self.current.pop(n, None)
                    continue
                current = self.current[n] = (key, skill)
            step = current[1].step(mine, me)
            for cmd in step.commands:
                if cmd[0] != "say":
                    self.sim.command(self.side, n, cmd[0], *cmd[1:])
            if step.status != "running":
                self.current.pop(n, None)
        for passer, action in asked:
            for n, st in states.items():
                if self.says and n != passer:
                    continue  # heard through the say, next cycle
                if st.ball and st.ball.positioning:  # the passer keeps his own, as the decision node does
                    ball = (st.ball.positioning.x, st.ball.positioning.y)
                    offside = offside_mates(st, ball)
                    self.passes.setdefault(n, {})[passer] = Announced(passer, action, ball, st.time + 1, offside)
                    if n != passer:
                        self.touches.setdefault(n, LastTouch()).played_by_mate(st.time if n in offside else None)

    def _read_says(self, n: int, st) -> None:
        """The passes player ``n`` heard said (``--talk say``), as the decision component reads them."""
        for passer, action, when in self.listeners.setdefault(n, Listener()).hear(st):
            if st.ball and st.ball.positioning:
                ball = (st.ball.positioning.x, st.ball.positioning.y)
                offside = offside_mates(st, ball)
                self.passes.setdefault(n, {})[passer] = Announced(passer, action, ball, when, offside)
                self.touches.setdefault(n, LastTouch()).played_by_mate(when if n in offside else None)

    def write_logs(self) -> None:
        """Each player's decision log, where ``tools/rcss_match.py --out`` puts our players' logs."""
        if self.log_dir is None:
            return
        self.log_dir.mkdir(parents=True, exist_ok=True)
        for n, lines in self.logs.items():
            (self.log_dir / f"{self.team}_{n}_decision.log").write_text("\n".join(lines) + "\n")


def play(
    seed: int,
    players: int,
    half_cycles: int,
    opponent: str = "chasers",
    out: Path | None = None,
    types: int = 18,
    talk: str = "framework",
) -> dict:
    sim = Simulator(
        Params(half_cycles=half_cycles, auto_kick_off_cycles=5),
        team_sizes=(players, players),
        team_names=("CF", "CFB" if opponent == "ours" else "chasers"),
        seed=seed,
        player_types=types,
    )
    match = out / f"match-{seed}" if out else None
    ours = PolicyTeam(sim, Side.LEFT, seed, match / "logs-CF" if match else None, talk)
    theirs = (
        PolicyTeam(sim, Side.RIGHT, seed + 1000, match / "logs-CFB" if match else None, talk)
        if opponent == "ours"
        else None
    )
    log = MatchLog(match / "match.jsonl", sim, 0.1) if match else None
    offsides = fouls = 0  # ours: a player of ours called offside; a tackle of ours called a foul
    while not sim.finished:
        ours.commands()
        if theirs:
            theirs.commands()
        else:
            chase_commands(sim, Side.RIGHT)
        events = sim.step()
        offsides += sum(e.startswith(f"offside {Side.LEFT.value} ") for e in events)
        fouls += sum(e.startswith(f"foul {Side.LEFT.value} ") for e in events)
        if log:
            log.cycle(sim.snapshot(), events)
    if log and match:
        log.close()
        export(match / "match.jsonl", match / "match.rcg")
        for team in (ours, theirs):
            if team:
                team.write_logs()
    w = sim.world
    return {
        "seed": seed,
        "ours": w.score[Side.LEFT],
        "theirs": w.score[Side.RIGHT],
        "shots": sim.stats["shots"][Side.LEFT],
        "kicks": sim.stats["kicks"][Side.LEFT],
        "possession": sim.stats["possession"][Side.LEFT] / max(1, sum(sim.stats["possession"].values())),
        "offsides": offsides,
        "fouls": fouls,
    }


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--matches", type=int, default=10)
    parser.add_argument("--players", type=int, default=11)
    parser.add_argument("--half-cycles", type=int, default=1500)
    parser.add_argument("--opponent", choices=("chasers", "ours"), default="chasers")
    parser.add_argument("--out", type=Path, help="keep each match's logs here (match-SEED/)")
    parser.add_argument(
        "--player-types", type=int, default=18, help="heterogeneous types as rcssserver 19's (1: all default)"
    )
    parser.add_argument(
        "--talk", choices=("framework", "say"), default="framework", help="say: team-mates talk only by say and hear"
    )
    args = parser.parse_args()
    rows = [
        play(seed, args.players, args.half_cycles, args.opponent, args.out, args.player_types, args.talk)
        for seed in range(args.matches)
    ]
    them = "chasers" if args.opponent == "chasers" else "cf_decision"
    talk = "" if args.talk == "framework" else ", talk by say"
    print(
        f"{args.players} v {args.players}, {2 * args.half_cycles} cycles a match{talk}, cf_decision (left) v {them}\n"
    )
    print(
        f"| seed | cf_decision | {them} | result | our shots | our kicks | our possession | our offsides | our fouls |"
    )
    print("|---:|---:|---:|---|---:|---:|---:|---:|---:|")
    for r in rows:
        result = "win" if r["ours"] > r["theirs"] else "draw" if r["ours"] == r["theirs"] else "loss"
        print(
            f"| {r['seed']} | {r['ours']} | {r['theirs']} | {result} | {r['shots']} | {r['kicks']} "
            f"| {r['possession']:.0%} | {r['offsides']} | {r['fouls']} |"
        )
    wins = sum(r["ours"] > r["theirs"] for r in rows)
    draws = sum(r["ours"] == r["theirs"] for r in rows)
    gd = sum(r["ours"] - r["theirs"] for r in rows)
    print(
        f"\nwins {wins}, draws {draws}, losses {len(rows) - wins - draws}; goals "
        f"{sum(r['ours'] for r in rows)}:{sum(r['theirs'] for r in rows)} (difference {gd:+d}); "
        f"median goal difference per match {statistics.median(r['ours'] - r['theirs'] for r in rows):+.1f}; "
        f"our offsides {sum(r['offsides'] for r in rows)}, fouls {sum(r['fouls'] for r in rows)}"
    )


if __name__ == "__main__":
    main()
