"""cf_lang.loads/dumps against sexpdata on the same inputs, side by side in one run.

Inputs: a small instance, the paper's exec inside a full FIPA-ACL request, and
a ~3 KB world state (22 players and the ball, with uncertainty). Each round
times every variant once on a batch (interleaved, so machine noise hits all
alike); the table gives the median messages per second and the ratio.

    python bench/bench_sexp.py [--rounds 15]
"""

from __future__ import annotations

import argparse
import random
import statistics
import time

import sexpdata

from cf_lang import dumps, loads, unparse
from cf_lang.acl import AclMessage, AgentId, Performative, from_sexp, parse, to_sexp, to_text
from cf_lang.ontology import AbsolutePositioning, Ball, Game, Player, Team, Velocity, WorldState


def inputs() -> dict[str, str]:
    rng = random.Random(7)

    def pos(sigma: float) -> AbsolutePositioning:
        return AbsolutePositioning(
            x=round(rng.uniform(-52, 52), 3),
            y=round(rng.uniform(-34, 34), 3),
            yaw=round(rng.uniform(-3.1, 3.1), 4),
            sigma_x=sigma,
            sigma_y=sigma,
        )

    players = tuple(
        Player(
            player_number=i % 11 + 1,
            which_team=Team.OUR if i < 11 else Team.OPP,
            positioning=pos(round(rng.uniform(0.05, 2.0), 3)),
            velocity=Velocity(vx=round(rng.uniform(-1, 1), 3), vy=round(rng.uniform(-1, 1), 3)),
        )
        for i in range(22)
    )
    world = WorldState(
        time=1234,
        ball=Ball(positioning=pos(0.1), velocity=Velocity(vx=1.2, vy=-0.4)),
        players=players,
        game=Game(time=1234, score_our=1),
    )
    paper_exec = "(exec Player turnToObject :playerNum 3 :whichTeam our :obj (Player :playerNum 4 :whichTeam our))"
    request = AclMessage(
        Performative.REQUEST,
        sender=AgentId("blue_3_decision"),
        receivers=(AgentId("blue_3_action"),),
        content=paper_exec,
        protocol="fipa-request",
        conversation_id="blue_3_decision-c42",
        reply_with="blue_3_decision-c42-r1",
        reply_by=1_795_000_000.123,
    )
    return {
        "small instance": "(AbsolutePositioning :x 10.3 :y -23.67 :yaw 0.23456)",
        "paper exec in ACL request": to_text(request),
        "world state, 22 players": unparse(world),
    }


def batch_seconds(fn, arg, n: int) -> float:
    start = time.perf_counter()
    for _ in range(n):
        fn(arg)
    return time.perf_counter() - start


def rates(variants: dict, n: int, rounds: int) -> dict[str, float]:
    """Calls per second of each ``name: (fn, arg)``: batches of n, interleaved round by round, medians."""
    times: dict[str, list[float]] = {k: [] for k in variants}
    for _ in range(rounds):
        for name, (fn, arg) in variants.items():
            times[name].append(batch_seconds(fn, arg, n))
    return {k: n / statistics.median(v) for k, v in times.items()}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=15)
    args = parser.parse_args()
    rows = []
    for label, text in inputs().items():
        ours_value, theirs_value = loads(text), sexpdata.loads(text)
        assert loads(dumps(ours_value)) == ours_value
        n = max(20, int(200_000 / len(text)))
        variants = {
            "cf_lang.loads": (loads, text),
            "sexpdata.loads": (sexpdata.loads, text),
            "cf_lang.dumps": (dumps, ours_value),
            "sexpdata.dumps": (sexpdata.dumps, theirs_value),
        }
        rows.append((label, len(text), rates(variants, n, args.rounds)))
    print(
        "| input | bytes | cf_lang loads msg/s | sexpdata loads msg/s | ratio | cf_lang dumps msg/s "
        "| sexpdata dumps msg/s | ratio |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, size, r in rows:
        print(
            f"| {label} | {size} | {r['cf_lang.loads']:,.0f} | {r['sexpdata.loads']:,.0f} "
            f"| **{r['cf_lang.loads'] / r['sexpdata.loads']:.1f}x** | {r['cf_lang.dumps']:,.0f} "
            f"| {r['sexpdata.dumps']:,.0f} | **{r['cf_lang.dumps'] / r['sexpdata.dumps']:.1f}x** |"
        )

    acl_table(args.rounds)


def acl_table(rounds: int) -> None:
    """ACL messages: the fast reader and the direct writer against the general path, same inputs."""
    common = AclMessage(
        Performative.REQUEST,
        sender=AgentId("blue_3_decision"),
        receivers=(AgentId("blue_3_action"),),
        content="(exec Player kick :playerNumber 3 :whichTeam our :power 80 :direction 0.1)",
        protocol="fipa-request",
        conversation_id="c42",
        reply_with="r1",
    )
    echo = AclMessage(Performative.INFORM, sender=AgentId("rt"), receivers=(AgentId("echo"),), content="123")
    messages = {
        "request, common shape": common,
        "short inform": echo,
        "request with :reply-by": common.with_(reply_by=1_795_000_000.123),
    }
    print(
        "\n| ACL message | bytes | acl.parse msg/s | loads + from_sexp msg/s | ratio | to_text msg/s | dumps(to_sexp) msg/s | ratio |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, msg in messages.items():
        text = to_text(msg)
        assert parse(text) == from_sexp(loads(text)) == msg and text == dumps(to_sexp(msg))
        variants = {
            "parse": (parse, text),
            "full": (lambda t: from_sexp(loads(t)), text),
            "to_text": (to_text, msg),
            "general": (lambda m: dumps(to_sexp(m)), msg),
        }
        r = rates(variants, 20_000, rounds)
        print(
            f"| {label} | {len(text)} | {r['parse']:,.0f} | {r['full']:,.0f} | **{r['parse'] / r['full']:.1f}x** "
            f"| {r['to_text']:,.0f} | {r['general']:,.0f} | **{r['to_text'] / r['general']:.1f}x** |"
        )


if __name__ == "__main__":
    main()
