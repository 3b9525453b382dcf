"""The ComMAg with real processes over real DDS: relaunch, withdrawal, restart, allowlist, taxonomy."""

from __future__ import annotations

import json
import os
import signal
from pathlib import Path

from cf_interfaces.msg import ComponentRecord
from cf_interfaces.srv import Lookup, Register
from cf_system import start_commag, start_component


def saved_names(registry: Path) -> set[str]:
    """The component names in a ComMAg's registry file (none while it is missing or half renamed)."""
    try:
        return {c["record"]["name"] for c in json.loads(registry.read_text())["components"]}
    except (OSError, ValueError, KeyError):
        return set()


def pid_of(probe, name):
    """Pids of the processes running component ``name`` (found by command line)."""
    import subprocess

    out = subprocess.run(["pgrep", "-f", "--", f"--name {name} "], capture_output=True, text=True).stdout.split()
    return [int(p) for p in out]


def since(probe, name, start):
    """Registry event kinds of ``name`` from the ``start``-th on, renewals left out.

    On a loaded machine a component may miss a lease (suspect, then renewed) before the test
    kills it: the kill is then seen from suspect already.
    """
    return [k for k in probe.kinds(name)[start:] if k != "renewed"]


def test_killed_component_is_relaunched_and_healthy_again(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    name = f"kick_{tag}"
    comp = start_component(procs, tag, name, "--service-class", "Kick", "--lease", "0.5", "--team", "blue")
    probe.wait_kind(name, "registered")
    killed_at = len(probe.kinds(name))
    os.kill(comp.pid, signal.SIGKILL)
    relaunched = probe.wait_kind(name, "relaunched")
    assert relaunched.record.state == "healthy"
    assert since(probe, name, killed_at) in (["suspect", "relaunching", "relaunched"], ["relaunching", "relaunched"])
    suspect = probe.wait_kind(name, "suspect", count=probe.kinds(name).count("suspect"))
    assert "missed its lease" in suspect.reason
    assert probe.lookup("Kick", team="blue") == [name]
    # The new process is a different one and it serves requests.
    new_pids = pid_of(probe, name)
    assert new_pids and comp.pid not in new_pids
    assert "up (pid" in (tmp_path / "component-logs" / f"{name}.log").read_text()


def test_a_relaunch_slower_than_the_start_up_grace_is_waited_for_while_its_process_runs(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path, "startup_grace:=1.0", "alive_grace:=20.0")
    name = f"slow_{tag}"
    comp = start_component(procs, tag, name, "--service-class", "Kick", "--lease", "0.5", "--relaunch-slow", "4")
    probe.wait_kind(name, "registered")
    killed_at = len(probe.kinds(name))
    os.kill(comp.pid, signal.SIGKILL)
    relaunched = probe.wait_kind(name, "relaunched", timeout=60)
    assert relaunched.record.state == "healthy"
    # One launch, waited for past the start-up grace: not killed and started again.
    assert since(probe, name, killed_at) in (["suspect", "relaunching", "relaunched"], ["relaunching", "relaunched"])
    assert "starting in 4.0 s" in (tmp_path / "component-logs" / f"{name}.log").read_text()


def test_repeatedly_failing_component_is_withdrawn_and_lookup_reroutes(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path, "max_failures:=3", "backoff_initial:=0.3", "backoff_max:=2.0")
    failing, twin = f"a_kick_{tag}", f"b_kick_{tag}"
    comp = start_component(procs, tag, failing, "--service-class", "Kick", "--lease", "0.5", "--relaunch-fails")
    start_component(procs, tag, twin, "--service-class", "Kick", "--lease", "0.5")
    probe.wait_kind(failing, "registered")
    probe.wait_kind(twin, "registered")
    assert probe.lookup("Kick") == [failing, twin]  # by name among equals
    os.kill(comp.pid, signal.SIGKILL)
    withdrawn = probe.wait_kind(failing, "withdrawn", timeout=60)
    assert withdrawn.record.state == "withdrawn" and withdrawn.record.failures == 3
    failed = [e.reason for e in probe.events if e.record.name == failing and e.kind_name == "launch_failed"]
    assert len(failed) == 3
    assert "exited with code 3" in failed[0]
    assert "next attempt in 0.30 s" in failed[0] and "next attempt in 0.60 s" in failed[1]
    assert probe.lookup("Kick") == [twin]
    assert probe.lookup("Kick", include_suspect=True) == [twin]


def two_movement_components(procs, probe, tag, tmp_path):
    """A ComMAg with a Dash and a Turn component registered: (the ComMAg, their names, their pids)."""
    commag = start_commag(procs, tag, tmp_path)
    names = [f"a_dash_{tag}", f"b_turn_{tag}"]
    start_component(procs, tag, names[0], "--service-class", "Dash", "--lease", "0.5")
    start_component(procs, tag, names[1], "--service-class", "Turn", "--lease", "0.5")
    for name in names:
        probe.wait_kind(name, "registered")
    return commag, names, {n: pid_of(probe, n) for n in names}


def test_commag_killed_and_restarted_keeps_every_registration(procs, probe, tag, tmp_path):
    commag, names, pids_before = two_movement_components(procs, probe, tag, tmp_path)
    # The registry file is written by the saver thread a moment after the events (a registration
    # killed before it is saved comes back by the component's next renewal instead): kill once saved.
    registry = tmp_path / "registry.json"
    probe.spin_until(lambda: saved_names(registry) >= set(names), timeout=10, what="both registrations saved")
    os.kill(commag.pid, signal.SIGKILL)
    commag.wait()
    probe.events.clear()
    start_commag(procs, tag, tmp_path, log_name="commag-restarted")
    assert probe.lookup("Movement", direction=Lookup.Request.SPECIFIC) == names
    probe.spin_for(3.0)  # six leases: every component renews, none is relaunched
    # (On a loaded machine a renewal may come a few ms late: suspect for a moment, never relaunched.)
    faults = [(e.record.name, e.kind_name, e.reason) for e in probe.events]
    assert not [f for f in faults if f[1] in ("relaunching", "withdrawn")], faults
    probe.spin_until(lambda: probe.lookup("Movement", direction=Lookup.Request.SPECIFIC) == names, 10, "both healthy")
    assert {n: pid_of(probe, n) for n in names} == pids_before
    assert "2 component(s) restored" in procs.log("commag-restarted")


def test_registrations_a_restarted_commag_never_saved_come_back_by_the_components_renewals(procs, probe, tag, tmp_path):
    """A ComMAg killed before its saver wrote a registration (here: started again on an empty file)."""
    commag, names, pids_before = two_movement_components(procs, probe, tag, tmp_path)
    os.kill(commag.pid, signal.SIGKILL)
    commag.wait()
    probe.events.clear()
    start_commag(procs, tag, tmp_path, f"persistence_path:={tmp_path / 'empty.json'}", log_name="commag-restarted")
    for name in names:  # each renewal is a whole registration: the new ComMAg takes it as one
        probe.wait_kind(name, "registered", timeout=20)
    assert probe.lookup("Movement", direction=Lookup.Request.SPECIFIC) == names
    assert not [e for e in probe.events if e.kind_name in ("relaunching", "withdrawn")]
    assert {n: pid_of(probe, n) for n in names} == pids_before
    assert "0 component(s) restored" in procs.log("commag-restarted")
    probe.spin_until(lambda: saved_names(tmp_path / "empty.json") == set(names), timeout=10, what="saved again")


def test_launch_command_outside_the_allowlist_is_refused(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    evil = ComponentRecord(name=f"evil_{tag}", service_class="Kick", launch_command=["/bin/sh", "-c", "touch /tmp/x"])
    res = probe.call(probe.register, Register.Request(component=evil))
    assert not res.accepted
    assert "launch command refused" in res.reason and "allowlist" in res.reason
    assert probe.lookup("Kick") == []


def test_lookup_honours_the_taxonomy_both_ways(procs, probe, tag, tmp_path):
    start_commag(procs, tag, tmp_path)
    general, specific = f"a_action_{tag}", f"b_shoot_{tag}"
    start_component(procs, tag, general, "--service-class", "Action")
    start_component(procs, tag, specific, "--service-class", "Shoot")
    probe.wait_kind(general, "registered")
    probe.wait_kind(specific, "registered")
    assert probe.lookup("Kick") == [general]  # a general provider serves a specific request
    assert probe.lookup("Kick", direction=Lookup.Request.SPECIFIC) == [specific]
    assert probe.lookup("Kick", direction=Lookup.Request.BOTH) == [specific, general]
    assert probe.lookup("Shoot") == [specific, general]
    assert probe.lookup("Kick", direction=Lookup.Request.EXACT) == []
