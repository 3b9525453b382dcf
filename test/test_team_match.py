"""A short match of decision components over DDS, with a redundant action provider taken away.

Two blue players (perception, action, decision each; player 2 has a second action provider) against
one red player. Midway blue 2's action provider in use is killed: blue 2 keeps playing through its
twin at once, and the ComMAg relaunches the killed one.
"""

from __future__ import annotations

import os
import signal

from test_sim_match import start_player_component, start_sim_process

from cf_interfaces.srv import Lookup
from cf_system import executable, last_match_record, match_ended, match_lines, start_commag


def start_decision(procs, tag, number, team_size):
    argv = [
        executable("cf_decision", "decision"),
        "--ros-args",
        "-r",
        f"__node:=decision_{number}_{tag}",
        "-p",
        f"commag:=/commag_{tag}",
        "-p",
        f"team:=blue{tag}",
        "-p",
        f"number:={number}",
        "-p",
        f"team_size:={team_size}",
        "-p",
        "lease:=0.5",
    ]
    return procs.start(argv, f"decision_{number}")


def test_decision_team_plays_and_survives_losing_an_action_provider(procs, probe, tag, tmp_path):
    # On a loaded machine (two suites side by side) a relaunched process took more than the default
    # 5 s to start and register, and each retry killed the slow one: give it the time.
    start_commag(procs, tag, tmp_path, "startup_grace:=20.0")
    start_sim_process(procs, tag, tmp_path, half_cycles=500)
    for number in (1, 2):
        start_player_component(procs, tag, "perception", "l", number)
        start_player_component(procs, tag, "action", "l", number)
        start_decision(procs, tag, number, 2)
    twin = procs.start(
        [
            executable("cf_sim_backend", "action"),
            "--ros-args",
            "-r",
            f"__node:=action_l2b_{tag}",
            "-p",
            f"sim:=sim_{tag}",
            "-p",
            f"commag:=/commag_{tag}",
            "-p",
            "side:=l",
            "-p",
            "number:=2",
            "-p",
            f"team:=blue{tag}",
            "-p",
            f"name:=blue{tag}_2_action_twin",
            "-p",
            "lease:=0.5",
        ],
        "action_l2_twin",
    )
    assert twin.poll() is None
    start_player_component(procs, tag, "perception", "r", 1)
    start_player_component(procs, tag, "action", "r", 1)
    first = f"blue{tag}_2_action"
    probe.wait_kind(f"blue{tag}_2_decision", "registered", timeout=60)
    probe.wait_kind(first, "registered", timeout=60)
    probe.wait_kind(f"blue{tag}_2_action_twin", "registered", timeout=60)
    log = tmp_path / "match.jsonl"

    # Both blue players move: their positions change from the kick-off formation.
    def moved(number):
        last = last_match_record(log)
        return any(
            p[0] == "l" and p[1] == number and (abs(p[2]) > 1 and abs(p[4]) + abs(p[5]) > 0.01)
            for p in last.get("players", [])
        )

    probe.spin_until(lambda: len(match_lines(log)) > 120, timeout=60, what="play")
    probe.spin_until(lambda: moved(2), timeout=30, what="blue 2 moving")
    # Take away the provider in use: "a_" sorts first, so the original is the one in use.
    pid = next(p for p in procs.procs if "action_l2" in " ".join(p.args) and "twin" not in " ".join(p.args)).pid
    os.kill(pid, signal.SIGKILL)
    probe.wait_kind(first, "suspect", timeout=20)
    probe.spin_until(lambda: moved(2), timeout=10, what="blue 2 still playing through the twin")
    probe.wait_kind(first, "relaunched", timeout=60)
    probe.spin_until(lambda: match_ended(log), timeout=120, what="the end of the match")
    end = last_match_record(log)
    assert end["stats"]["kicks"]["l"] > 0, end  # the decision team played the ball


def test_a_commag_killed_mid_match_comes_back_by_itself_and_loses_no_registration(procs, probe, tag, tmp_path):
    """The ComMAg under its supervisor (what the demo, rcss_team and the launch files' respawn do)."""
    import subprocess

    commag = [executable("cf_commag", "commag"), "--ros-args", "-r", f"__node:=commag_{tag}"]
    commag += ["-p", f"persistence_path:={tmp_path / 'registry.json'}", "-p", f"log_dir:={tmp_path / 'logs'}"]
    supervisor = procs.start([executable("cf_commag", "supervise"), "--delay", "0.5", "--", *commag], "supervise")
    start_sim_process(procs, tag, tmp_path, half_cycles=600)
    start_player_component(procs, tag, "perception", "l", 1)
    start_player_component(procs, tag, "action", "l", 1)
    start_decision(procs, tag, 1, 1)
    start_player_component(procs, tag, "perception", "r", 1)
    start_player_component(procs, tag, "action", "r", 1)
    names = {f"blue{tag}_1_decision", f"blue{tag}_1_perception", f"blue{tag}_1_action"}
    for name in names:
        probe.wait_kind(name, "registered", timeout=60)
    log = tmp_path / "match.jsonl"
    probe.spin_until(lambda: len(match_lines(log)) > 100, timeout=60, what="play")
    before = set(probe.lookup("Service", direction=Lookup.Request.SPECIFIC))  # every component

    def commag_pid():
        out = subprocess.run(["pgrep", "-P", str(supervisor.pid)], capture_output=True, text=True).stdout.split()
        return int(out[0]) if out else None

    first = commag_pid()
    assert first is not None
    os.kill(first, signal.SIGKILL)
    cycles_at_kill = len(match_lines(log))
    probe.spin_until(lambda: commag_pid() not in (None, first), timeout=30, what="the supervisor to start it again")
    # The new ComMAg restored every registration and its lookups answer as before.
    everyone = {"direction": Lookup.Request.SPECIFIC}
    probe.spin_until(lambda: set(probe.lookup("Service", **everyone)) >= before, timeout=60, what="registrations")
    assert names <= before
    # Nobody was relaunched or withdrawn because of it: the components kept renewing to the new ComMAg.
    probe.spin_for(3.0)
    assert not [e for e in probe.events if e.kind_name in ("withdrawn", "relaunching") and e.record.name in names]
    probe.spin_until(lambda: len(match_lines(log)) > cycles_at_kill + 100, 60, "the match going on")
    assert "started again as pid" in procs.log("supervise")
