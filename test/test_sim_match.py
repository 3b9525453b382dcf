"""A short real match over DDS: the simulator, perception and action components in their own processes.

A scripted decision (in this test) finds its player's components through the ComMAg and keeps asking
for intercept-then-shoot. Midway the action component is killed; the ComMAg relaunches it and play goes on.
"""

from __future__ import annotations

import json
import os
import signal
import time

from cf_commag.client import Agent
from cf_system import executable, last_match_record, match_ended, match_lines, start_commag


def start_sim_process(procs, tag, tmp_path, **params):
    args = {
        "sim": f"sim_{tag}",
        "commag": f"/commag_{tag}",
        "cycle_period": 0.05,
        "half_cycles": 400,
        "halves": 1,
        "auto_kick_off_cycles": 5,
        "left_size": 2,
        "right_size": 1,
        "match_log": str(tmp_path / "match.jsonl"),
        **params,
    }
    argv = [executable("cf_sim_backend", "sim"), "--ros-args", "-r", f"__node:=sim_{tag}"]
    for k, v in args.items():
        argv += ["-p", f"{k}:={v}"]
    return procs.start(argv, "sim")


def start_player_component(procs, tag, role, side, number):
    argv = [
        executable("cf_sim_backend", role),
        "--ros-args",
        "-r",
        f"__node:={role}_{side}{number}_{tag}",
        "-p",
        f"sim:=sim_{tag}",
        "-p",
        f"commag:=/commag_{tag}",
        "-p",
        f"side:={side}",
        "-p",
        f"number:={number}",
        "-p",
        f"team:={'blue' if side == 'l' else 'red'}{tag}",
        "-p",
        "lease:=0.5",
    ]
    return procs.start(argv, f"{role}_{side}{number}")


def test_short_match_with_a_component_killed_and_relaunched(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    start_sim_process(procs, tag, tmp_path, half_cycles=1600)  # long enough to play on after the relaunch
    team = f"blue{tag}"
    action = {}
    for number in (1, 2):
        start_player_component(procs, tag, "perception", "l", number)
        action[number] = start_player_component(procs, tag, "action", "l", number)
    start_player_component(procs, tag, "perception", "r", 1)
    start_player_component(procs, tag, "action", "r", 1)

    decision = Agent(probe.node, name=f"decision_{tag}", service_class="PlayerDecision", commag=f"/commag_{tag}")
    probe.spin_until(
        lambda: len(decision.providers("Action", team=team)) == 2, timeout=60, what="both action providers"
    )
    action_name = decision.provider("Action", team=team, player_number=2)

    # The perception answers in the Framework Language.
    perception = probe.spin_until(
        lambda: decision.provider("WorldModel", team=team, player_number=2), timeout=60, what="a perception provider"
    )

    def game():
        future = decision.request(perception, "(val Game)", protocol="fipa-query", timeout=5)
        probe.spin_until(future.done, what="perception answer")
        reply = future.result()
        # Registered before the simulator's first cycle reached it (a loaded machine): ask again.
        return None if "simulator has not started" in (reply.content or "") else reply

    reply = probe.spin_until(game, timeout=60, what="the perception's answer once the simulator runs")
    assert reply.ok and reply.content.startswith("(Game :time")

    def play(number, wanted, seconds=90.0):
        """Ask for intercept, then shoot, until `wanted` requests were done; returns the answers seen.

        Some requests may fail on the way (the ball held in the other side's set piece, a shot
        replaced by the next request), so it keeps asking until the deadline.
        """
        answers = []
        deadline = time.monotonic() + seconds
        while sum(a == "done" for a in answers) < wanted and time.monotonic() < deadline:
            for method in ("intercept", "shoot"):
                provider = decision.provider("Action", team=team, player_number=number)
                if provider is None:
                    probe.spin_for(0.2)
                    continue
                req = decision.request(
                    provider, f"(exec Player {method} :playerNumber {number} :whichTeam our)", timeout=20
                )  # generous: their set piece can hold the ball for up to 100 cycles
                probe.spin_until(req.done, timeout=30, what=f"{method} answer")
                answers.append(req.result().state)
        return answers

    answers = play(2, 2)
    assert answers.count("done") >= 2, answers
    # Bad requests are answered, not ignored.
    req = decision.request(action_name, "(exec Player fly :playerNumber 2 :whichTeam our)")
    probe.spin_until(req.done)
    assert req.result().state == "not-understood" and "no method fly" in req.result().content

    os.kill(action[2].pid, signal.SIGKILL)
    probe.wait_kind(action_name, "suspect", timeout=20)
    probe.wait_kind(action_name, "relaunched", timeout=30)
    answers = play(2, 2)
    assert answers.count("done") >= 2, answers  # the relaunched component plays on

    probe.spin_until(lambda: match_ended(tmp_path / "match.jsonl"), timeout=240, what="the end of the match")
    lines = match_lines(tmp_path / "match.jsonl")
    header, end = json.loads(lines[0]), json.loads(lines[-1])
    assert header["format"] == "cf-match-log" and header["teams"]["l"] == "blue"
    assert end["stats"]["kicks"]["l"] > 0
    cycles = [json.loads(x) for x in lines[1:-1]]
    assert cycles[-1]["mode"] == "time_over" and len(cycles) >= 1600


def test_sync_mode_steps_when_every_player_has_acted(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    start_sim_process(procs, tag, tmp_path, mode="sync", left_size=1, right_size=1, half_cycles=300)
    for side in ("l", "r"):
        start_player_component(procs, tag, "action", side, 1)
    log = tmp_path / "match.jsonl"
    probe.spin_until(lambda: match_ended(log), timeout=120, what="the end of the match")
    end = last_match_record(log)
    # Only the cycles before both action components were up waited for the timeout; the rest went in lockstep.
    assert end["sync"]["steps"] >= 300
    assert end["sync"]["steps"] - end["sync"]["timeouts"] >= 250, end["sync"]
