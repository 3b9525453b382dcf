"""A component container (the players executable) as the ComMAg sees it: real processes, kill -9 and SIGSTOP.

Two players' perception, action and decision (6 agents) share one process. Killed, the process is
relaunched once and every agent in it comes back; stopped (hung: it runs but does nothing), it is
given ``alive_grace`` beyond the lease, then killed and relaunched. Meanwhile the agents are
found by lookup and answer agents of other processes, as components alone in a process do.
"""

from __future__ import annotations

import os
import signal

from test_sim_match import start_sim_process

from cf_commag.client import Agent
from cf_commag.process import process_start
from cf_commag.testing import Ros
from cf_system import last_match_record, match_ended, players_argv, start_commag

AGENTS = [f"blue_{n}_{role}" for n in (1, 2) for role in ("perception", "action", "decision")]


def start_players(procs, tag):
    return procs.start(players_argv(tag, "l", f"players_{tag}", "team_size:=2", "lease:=1.0"), "players")


def registered_pid(probe, name: str) -> int:
    """The pid the registry snapshot names for agent ``name``."""
    probe.spin_until(lambda: probe.snapshot and any(r.name == name for r in probe.snapshot.records), 30.0)
    record = next(r for r in probe.snapshot.records if r.name == name)
    return int(next(kv.value for kv in record.metadata if kv.key == "pid"))


def pids(probe) -> set[int]:
    return {registered_pid(probe, name) for name in AGENTS}


def launches(probe) -> list:
    """Processes the ComMAg started: relaunch events that did not join a launch under way."""
    return [e for e in probe.events if e.kind_name == "relaunching" and "with its host" not in e.reason]


def test_a_container_is_relaunched_once_for_all_its_agents_and_a_hung_one_is_killed_first(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path, "alive_grace:=3.0", "startup_grace:=20.0")
    first = start_players(procs, tag)
    for name in AGENTS:
        probe.wait_kind(name, "registered", timeout=60.0)
    probe.spin_until(lambda: pids(probe) == {first.pid}, 30.0, "every agent registered from the container")

    # Found like any component, and answering an agent of another process (this one) over DDS.
    assert probe.lookup("WorldModel", team="blue", player_number=2) == ["blue_2_perception"]
    node = Ros.node(probe, f"asker_{tag}")
    asker = Agent(node, name=f"asker_{tag}", service_class="Coaching", commag=f"/commag_{tag}")
    future = asker.request("blue_2_perception", "(val WorldState)", protocol="fipa-query", timeout=10.0)
    probe.spin_until(future.done, 30.0, "the hosted perception's answer")
    assert future.result().state == "failed" and "simulator has not started" in future.result().content

    # kill -9: one launch of the container, every agent back in the new process.
    os.killpg(first.pid, signal.SIGKILL)
    for name in AGENTS:
        probe.wait_kind(name, "relaunched", timeout=90.0)
    assert len(launches(probe)) == 1
    second = registered_pid(probe, "blue_1_decision")
    assert second != first.pid
    probe.spin_until(lambda: pids(probe) == {second}, 30.0, "every agent registered from the new process")

    # Hung (stopped: the process runs, nothing in it does): suspect, passed over, then killed and relaunched.
    os.kill(second, signal.SIGSTOP)
    suspect = probe.wait_kind("blue_1_perception", "suspect", count=2, timeout=30.0)
    assert "still runs (starved or hung)" in suspect.reason
    for name in AGENTS:
        probe.wait_kind(name, "relaunched", count=2, timeout=90.0)
    assert len(launches(probe)) == 2
    probe.spin_until(lambda: process_start(second) is None, 10.0, "the hung process killed")
    third = registered_pid(probe, "blue_1_decision")
    assert third not in (first.pid, second)


def test_two_containers_play_a_sync_match_every_player_acting_every_cycle(procs, probe, tag, tmp_path):
    """Each team in one process: one state read per process, each cycle's commands and dones as one sample."""
    start_commag(procs, tag, tmp_path)
    for side in ("l", "r"):
        team = f"team:={'blue' if side == 'l' else 'red'}{tag}"
        argv = players_argv(tag, side, f"players_{side}_{tag}", "team_size:=2", "lease:=2.0", team)
        procs.start(argv, f"players_{side}")
    for side in ("blue", "red"):
        for n in (1, 2):
            probe.wait_kind(f"{side}{tag}_{n}_decision", "registered", timeout=60.0)
    start_sim_process(procs, tag, tmp_path, mode="sync", left_size=2, right_size=2, half_cycles=300, sync_timeout=2.0)
    log = tmp_path / "match.jsonl"
    probe.spin_until(lambda: match_ended(log), timeout=180, what="the end of the match")
    end = last_match_record(log)
    # Lockstep: the simulator stepped when all four players' dones had come (in each process's one sample).
    assert end["sync"]["steps"] >= 300 and end["sync"]["timeouts"] <= 5, end["sync"]
    assert end["stats"]["kicks"]["l"] + end["stats"]["kicks"]["r"] > 0, end  # the decisions played the ball
    assert "command refused" not in procs.log("sim")
