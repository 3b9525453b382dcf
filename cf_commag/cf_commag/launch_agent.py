"""A launch agent: starts components on its machine when the ComMAg asks.

    ros2 run cf_commag launch_agent [--ros-args -p name:=launcher_b -p allowed_roots:="[/opt/team/install]"]

A ComMAg starts processes only on its own machine. For a team spread over several machines,
run one launch agent on each of the others (under ``supervise`` or launch's ``respawn``). It
registers with the ComMAg as a ``Launcher`` of its machine (metadata ``machine_name``:
``$CF_MACHINE``, else the host name) and serves ``/<name>/launch`` (cf_interfaces/srv/Launch).
When a component of that machine must be relaunched, the ComMAg asks it, and it starts the
component's launch command there: only a command its own allowlist allows (the same rules as
the ComMAg's, see launcher.py), as argv, never through a shell, output in ``<log_dir>/<name>.log``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from pydantic import Field
from rclpy.node import Node

from cf_interfaces.srv import Launch

from .agent import Agent
from .given_parameters import node_name as safe_node_name
from .guarded import GuardedNode
from .launcher import Launcher, LaunchPolicy, workspace_roots
from .params import ComponentParams
from .process import machine_name
from .registry import LaunchError
from .runtime import own_launch_command, run
from .transport.qos import SERVICE_QOS


class LaunchAgentParams(ComponentParams):
    """A launch agent's parameters (its name defaults to ``launcher_<machine>``)."""

    allowed_roots: tuple[str, ...] = Field((), description="directories whose executables may be launched")
    allowed_commands: tuple[str, ...] = Field((), description="further executables (absolute paths) allowed")
    log_dir: str = Field("", description="output of what it starts; empty = <ROS_HOME>/log/cf_launch_agent")
    lease: float = Field(2.0, gt=0, le=300, description="lease period (s) with the ComMAg")
    relaunch: bool = Field(
        False, description="register a launch command (only its own machine could run it: supervise it instead)"
    )
    kill_on_exit: bool = Field(False, description="kill what it started when it exits")


def _name(p: dict) -> str:
    return p["name"] or safe_node_name(f"launcher_{machine_name()}")


class LaunchAgentNode(GuardedNode, Node):
    """The launch agent of this machine. Parameters: LaunchAgentParams."""

    def __init__(self, **kwargs):
        super().__init__(_name(LaunchAgentParams.given(kwargs)), **kwargs)
        p = self.p = LaunchAgentParams.declare_and_read(self)
        roots = p.allowed_roots or workspace_roots()
        home = Path(os.environ.get("ROS_HOME", Path.home() / ".ros"))
        log_dir = Path(p.log_dir) if p.log_dir else home / "log" / "cf_launch_agent"
        self.launcher = Launcher(policy=LaunchPolicy(roots, p.allowed_commands), log_dir=log_dir)
        self.started = 0
        self.create_service(Launch, "~/launch", self._on_launch, qos_profile=SERVICE_QOS)
        self.create_timer(0.5, self._reap)
        self.agent = Agent(
            self,
            name=self.get_name(),
            service_class="Launcher",
            commag=p.commag,
            lease=p.lease,
            launch_command=p.launch_command(own_launch_command()),
        )
        self.get_logger().info(f"launch agent of machine {machine_name()!r}; allowlist roots={list(roots)}")

    def _on_launch(self, request: Launch.Request, response: Launch.Response) -> Launch.Response:
        try:
            response.pid = self.launcher.launch(request.name, tuple(request.argv))
        except LaunchError as exc:
            response.ok, response.reason = False, str(exc)
            self.get_logger().warning(f"{request.name}: not started: {exc}")
            return response
        self.started += 1
        response.ok = True
        self.get_logger().info(f"{request.name}: started {request.argv[0]} (pid {response.pid})")
        return response

    def _reap(self) -> None:
        for name, code in self.launcher.poll():
            self.get_logger().info(f"{name}: the process it started exited with code {code}")

    def stop(self) -> None:
        if self.p.kill_on_exit:
            self.launcher.stop_all()


def main(args: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_commag launch_agent``."""
    return run(LaunchAgentNode, on_exit=LaunchAgentNode.stop, args=args)


if __name__ == "__main__":
    sys.exit(main())
