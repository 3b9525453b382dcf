"""The launcher runs real processes: allowlist, argv without a shell, logs, reaping."""

from __future__ import annotations

import os
import stat
import time
from pathlib import Path

import pytest

from cf_commag.launcher import Launcher, LaunchPolicy, workspace_roots
from cf_commag.registry import LaunchError
from cf_commag.store import Saver, load, save


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    lib = tmp_path / "install" / "pkg" / "lib" / "pkg"
    lib.mkdir(parents=True)
    script = lib / "echo_args"
    script.write_text('#!/bin/sh\necho "args:$#:$1:$2"\nexit "${EXIT_CODE:-0}"\n')
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    return tmp_path


def wait_exit(launcher: Launcher, name: str, timeout: float = 10.0) -> int:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        for who, code in launcher.poll():
            if who == name:
                return code
        time.sleep(0.01)
    raise AssertionError(f"{name} did not exit")


def test_allowlist(workspace: Path):
    policy = LaunchPolicy(allowed_roots=(str(workspace / "install"),))
    exe = str(workspace / "install/pkg/lib/pkg/echo_args")
    assert policy.check((exe,)) is None
    assert "not in the ComMAg's allowlist" in policy.check(("/bin/sh", "-c", "true"))
    assert "not in the ComMAg's allowlist" in policy.check(("sh",))  # found on PATH, still refused
    assert "not an executable" in policy.check((str(workspace / "nope"),))
    assert policy.check(()) == "empty launch command"
    # A symlink inside the root that points outside it is judged by its target.
    (workspace / "install/pkg/lib/pkg/sneaky").symlink_to("/bin/sh")
    assert "allowlist" in policy.check((str(workspace / "install/pkg/lib/pkg/sneaky"),))
    assert LaunchPolicy(allowed_commands=("/bin/true",)).check(("/bin/true",)) is None


def test_runs_argv_without_a_shell_and_logs_output(workspace: Path):
    launcher = Launcher(LaunchPolicy(allowed_roots=(str(workspace / "install"),)), log_dir=workspace / "logs")
    marker = workspace / "pwned"
    exe = str(workspace / "install/pkg/lib/pkg/echo_args")
    launcher.launch("comp", (exe, f"; touch {marker}", "$(touch x)"))
    assert wait_exit(launcher, "comp") == 0
    log = (workspace / "logs" / "comp.log").read_text()
    assert f"args:2:; touch {marker}:$(touch x)" in log
    assert not marker.exists()


def test_refused_command_raises(workspace: Path):
    launcher = Launcher(LaunchPolicy(allowed_roots=(str(workspace / "install"),)), log_dir=workspace / "logs")
    with pytest.raises(LaunchError, match="allowlist"):
        launcher.launch("evil", ("/bin/sh", "-c", "echo hi"))


def test_exit_codes_are_reaped_no_zombies(workspace: Path):
    launcher = Launcher(
        LaunchPolicy(allowed_roots=(str(workspace / "install"),)),
        log_dir=workspace / "logs",
        env={**os.environ, "EXIT_CODE": "7"},
    )
    pid = launcher.launch("comp", (str(workspace / "install/pkg/lib/pkg/echo_args"),))
    assert wait_exit(launcher, "comp") == 7
    assert not Path(f"/proc/{pid}").exists()  # reaped, not a zombie


def test_relaunch_kills_the_previous_instance(workspace: Path):
    sleeper = workspace / "install/pkg/lib/pkg/sleeper"
    sleeper.write_text("#!/bin/sh\nexec sleep 30\n")
    sleeper.chmod(0o755)
    launcher = Launcher(LaunchPolicy(allowed_roots=(str(workspace / "install"),)), log_dir=workspace / "logs")
    first = launcher.launch("comp", (str(sleeper),))
    second = launcher.launch("comp", (str(sleeper),))
    assert first != second
    for _ in range(500):  # killed at once, reaped by a later poll (kill does not wait)
        launcher.poll()
        if not Path(f"/proc/{first}").exists():
            break
        time.sleep(0.01)
    assert not Path(f"/proc/{first}").exists()
    assert launcher.pid("comp") == second
    launcher.stop_all()
    assert not Path(f"/proc/{second}").exists()


def test_store_round_trip_and_corruption(tmp_path: Path):
    path = tmp_path / "sub" / "registry.json"
    assert load(path) == []
    save(path, [{"record": {"name": "a", "service_class": "Kick"}, "state": "healthy"}])
    assert load(path)[0]["record"]["name"] == "a"
    assert [p.name for p in path.parent.iterdir()] == ["registry.json"]  # no temp file left
    path.write_text("{not json")
    with pytest.raises(ValueError, match="not valid JSON"):
        load(path)


def test_saver_writes_the_latest_state_in_its_own_thread(tmp_path: Path):
    path = tmp_path / "registry.json"
    errors = []
    saver = Saver(path, on_error=errors.append)
    for i in range(50):
        saver.save([{"record": {"name": f"c{i}"}, "state": "healthy"}])
    saver.close()
    assert [e["record"]["name"] for e in load(path)] == ["c49"]  # the newest state won
    assert 1 <= saver.writes <= 50 and not errors


def test_saver_reports_a_disk_error_and_goes_on(tmp_path: Path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    errors = []
    saver = Saver(blocker / "registry.json", on_error=errors.append)  # its parent is a file
    saver.save([])
    saver.close()
    assert errors and isinstance(errors[0], OSError)


def test_the_install_space_is_found_also_when_colcon_linked_the_module_to_the_source(tmp_path):
    source = tmp_path / "src" / "cf_commag" / "cf_commag" / "launcher.py"
    source.parent.mkdir(parents=True)
    source.write_text("")
    prefix = tmp_path / "install" / "cf_commag"
    (prefix / "share" / "cf_commag").mkdir(parents=True)
    linked = prefix / "lib" / "python3" / "site-packages" / "cf_commag" / "launcher.py"
    linked.parent.mkdir(parents=True)
    linked.symlink_to(source)  # what `colcon build --symlink-install` makes
    assert workspace_roots(str(linked)) == (str(tmp_path / "install"),)
    assert workspace_roots(str(source)) == ()  # the source tree alone allows nothing
