"""The ComMAg as an rclpy lifecycle node: a thin shell around :class:`Registry`."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import time
from pathlib import Path

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from pydantic import Field
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.lifecycle import LifecycleNode, LifecycleState, TransitionCallbackReturn

from cf_interfaces.msg import Registry as RegistryMsg
from cf_interfaces.msg import RegistryEvent
from cf_interfaces.srv import Deregister, Launch, Lookup, Register
from cf_lang.taxonomy import Direction

from . import store
from .convert import event_to_msg, to_msg, to_query, to_record
from .guarded import GuardedNode
from .launcher import Launcher, LaunchPolicy, workspace_roots
from .params import NodeParams
from .process import machine_of, on_this_machine, running, running_command
from .records import EventKind, Query, Record, State
from .registry import Event, LaunchError, Registry, RegistryConfig, launch_key
from .runtime import run
from .transport.qos import EVENTS_QOS, SERVICE_QOS, SNAPSHOT_QOS

STALL = 0.25  # s: a tick this late means the ComMAg itself was not running
_LEVEL = {
    State.HEALTHY: DiagnosticStatus.OK,
    State.SUSPECT: DiagnosticStatus.WARN,
    State.RELAUNCHING: DiagnosticStatus.WARN,
    State.WITHDRAWN: DiagnosticStatus.ERROR,
}


def _ros_home() -> Path:
    return Path(os.environ.get("ROS_HOME", Path.home() / ".ros"))


class CommagConfig(NodeParams):
    """The ComMAg's parameters, read once in on_configure."""

    default_lease: float = Field(1.0, gt=0, description="lease (s) for components that do not ask for one")
    startup_grace: float = Field(5.0, gt=0, description="seconds a relaunched component has to re-register")
    max_failures: int = Field(3, ge=1, description="consecutive failed launches before withdrawal")
    backoff_initial: float = Field(0.5, ge=0, description="delay (s) after the first failed launch; doubles each time")
    backoff_max: float = Field(8.0, ge=0, description="cap (s) on the delay between launch attempts")
    stable_period: float = Field(30.0, ge=0, description="seconds healthy before the failure count resets")
    alive_grace: float = Field(
        10.0,
        ge=0,
        description="seconds beyond its lease a silent component whose process still runs (starved or hung) "
        "has before it is relaunched (the hung process is killed first)",
    )
    forget_after: float = Field(
        60.0,
        ge=0,
        description="seconds after which a withdrawn component without launch command is forgotten (0: never)",
    )
    tick_period: float = Field(0.05, gt=0, le=1.0, description="how often (s) leases are checked")
    allowed_roots: tuple[str, ...] = Field((), description="directories whose executables may be launched")
    allowed_commands: tuple[str, ...] = Field((), description="further executables (absolute paths) allowed")
    persistence_path: str = Field("", description="registry file; empty = <ROS_HOME>/cf_commag/registry.json")
    log_dir: str = Field("", description="component output logs; empty = <ROS_HOME>/log/cf_commag")
    publish_renewals: bool = Field(False, description="also publish an event for every plain renewal")
    diagnostics_period: float = Field(1.0, gt=0, description="seconds between /diagnostics messages")
    stop_launched_on_exit: bool = Field(False, description="kill the processes it launched when it exits")


class CommagNode(GuardedNode, LifecycleNode):
    """The Communication Management Agent (paper, section 3).

    Parameters: see CommagConfig (each declared with its description), plus
    ``autostart`` (bool, default true: configure and activate at start-up).

    Services: ``~/register`` (Register), ``~/deregister`` (Deregister),
    ``~/lookup`` (Lookup). Topics: ``~/events`` (RegistryEvent, transient local, last 1000),
    ``~/registry`` (Registry, transient local: late joiners get the latest),
    ``/diagnostics`` (DiagnosticArray, one status per component).
    Services answer "not active" unless the node is active.
    """

    def __init__(self, node_name: str = "commag", **kwargs):
        super().__init__(node_name, **kwargs)
        CommagConfig.declare(self)
        self.declare_parameter("autostart", True, ParameterDescriptor(description="configure and activate at start"))
        self._active = False
        self._registry: Registry | None = None
        self._launcher: Launcher | None = None
        self._policy: LaunchPolicy | None = None
        self._launch_clients: dict = {}  # launch agent name -> its Launch client
        self._tick_timers = []
        self._commag_services = []
        self._store_path: Path | None = None
        self._saver: store.Saver | None = None
        self._last_diag = 0.0
        self._last_tick = time.monotonic()
        self.stalls = 0  # ticks that came late by more than STALL

    # ---- lifecycle ---------------------------------------------------------

    def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
        try:
            cfg = CommagConfig.read(self)
        except ValueError as exc:
            self.get_logger().error(str(exc))
            return TransitionCallbackReturn.FAILURE
        self._cfg = cfg
        roots = cfg.allowed_roots or workspace_roots()
        policy = self._policy = LaunchPolicy(allowed_roots=roots, allowed_commands=cfg.allowed_commands)
        log_dir = Path(cfg.log_dir) if cfg.log_dir else _ros_home() / "log" / "cf_commag"
        self._launcher = Launcher(policy=policy, log_dir=log_dir)
        self._registry = Registry(
            RegistryConfig(
                default_lease=cfg.default_lease,
                startup_grace=cfg.startup_grace,
                max_failures=cfg.max_failures,
                backoff_initial=cfg.backoff_initial,
                backoff_max=cfg.backoff_max,
                stable_period=cfg.stable_period,
                forget_after=cfg.forget_after,
                alive_grace=cfg.alive_grace,
            ),
            launch=self._launch,
            check_launch=self._check_launch,
            cancel_launch=lambda key: self._launcher.kill(key),
            alive=lambda record: running(record.metadata),
            launch_running=lambda key: self._launcher.pid(key) is not None,
        )
        self._store_path = (
            Path(cfg.persistence_path) if cfg.persistence_path else _ros_home() / "cf_commag" / "registry.json"
        )
        try:
            restored = self._registry.restore(store.load(self._store_path), now=time.monotonic())
        except (ValueError, KeyError, TypeError) as exc:
            self.get_logger().error(f"cannot restore the registry: {exc}")
            return TransitionCallbackReturn.FAILURE
        self._registry.changed = False
        self.get_logger().info(
            f"configured: {restored} component(s) restored from {self._store_path}; "
            f"launch allowlist roots={list(roots)} commands={list(cfg.allowed_commands)}"
        )
        self._events_pub = self.create_lifecycle_publisher(RegistryEvent, "~/events", EVENTS_QOS)
        self._snapshot_pub = self.create_lifecycle_publisher(RegistryMsg, "~/registry", SNAPSHOT_QOS)
        self._diag_pub = self.create_lifecycle_publisher(DiagnosticArray, "/diagnostics", 10)
        self._commag_services = [
            self.create_service(Register, "~/register", self._on_register, qos_profile=SERVICE_QOS),
            self.create_service(Deregister, "~/deregister", self._on_deregister, qos_profile=SERVICE_QOS),
            self.create_service(Lookup, "~/lookup", self._on_lookup, qos_profile=SERVICE_QOS),
        ]
        return super().on_configure(state)

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        result = super().on_activate(state)
        self._active = True
        self._last_tick = time.monotonic()
        self._tick_timers = [self.create_timer(self._cfg.tick_period, self._on_tick)]
        self._publish_snapshot()
        self.get_logger().info("active")
        return result

    def on_deactivate(self, state: LifecycleState) -> TransitionCallbackReturn:
        self._active = False
        for timer in self._tick_timers:
            self.destroy_timer(timer)
        self._tick_timers = []
        self.close_store()
        return super().on_deactivate(state)

    def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
        for srv in self._commag_services:
            self.destroy_service(srv)
        self._commag_services = []
        for pub in (self._events_pub, self._snapshot_pub, self._diag_pub):
            self.destroy_lifecycle_publisher(pub)
        self._registry = None
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: LifecycleState) -> TransitionCallbackReturn:
        self._active = False
        self.close_store()
        return TransitionCallbackReturn.SUCCESS

    # ---- services ----------------------------------------------------------

    def _on_register(self, request: Register.Request, response: Register.Response) -> Register.Response:
        if not self._active:
            response.accepted, response.reason = False, "ComMAg is not active"
            return response
        try:
            result, events = self._registry.register(to_record(request.component), now=time.monotonic())
        except (ValueError, TypeError) as exc:
            response.accepted, response.reason = False, f"bad record: {exc}"
            return response
        response.accepted, response.reason, response.lease_period = result.accepted, result.reason, result.lease
        self._emit(events)
        return response

    def _on_deregister(self, request: Deregister.Request, response: Deregister.Response) -> Deregister.Response:
        if not self._active:
            response.accepted, response.reason = False, "ComMAg is not active"
            return response
        result, events = self._registry.deregister(request.name, now=time.monotonic())
        response.accepted, response.reason = result.accepted, result.reason
        self._emit(events)
        return response

    def _on_lookup(self, request: Lookup.Request, response: Lookup.Response) -> Lookup.Response:
        if not self._active:
            response.ok, response.reason = False, "ComMAg is not active"
            return response
        try:
            entries = self._registry.lookup(to_query(request))
        except ValueError as exc:
            response.ok, response.reason = False, str(exc)
            return response
        response.ok, response.reason = True, f"{len(entries)} provider(s)"
        response.providers = [to_msg(e.record, e) for e in entries]
        return response

    # ---- periodic work -----------------------------------------------------

    def _check_launch(self, record: Record) -> str | None:
        """Whether a record's launch command may run: ours to judge on this machine, its launch agent's elsewhere."""
        if not on_this_machine(record.metadata):
            return None
        return self._policy.check(record.launch_command)

    def _launch(self, record: Record) -> None:
        """Start a component (or its host) again; a hung process still running that command is killed first.

        A component of another machine is started there by that machine's launch agent.
        """
        if not on_this_machine(record.metadata):
            self._launch_remote(record)
            return
        stale = running_command(record.metadata, record.launch_command)
        if stale is not None:
            self.get_logger().warning(f"{record.name}: killing its hung process {stale} before relaunching it")
            with contextlib.suppress(OSError):
                os.kill(stale, signal.SIGKILL)
        self._launcher.launch(launch_key(record), record.launch_command)

    def _launch_remote(self, record: Record) -> None:
        machine = machine_of(record.metadata)
        agents = [
            e.name
            for e in self._registry.lookup(Query("Launcher", Direction.EXACT))
            if e.state is State.HEALTHY and machine_of(e.record.metadata) == machine
        ]
        if not agents:
            raise LaunchError(f"no launch agent on machine {machine!r} (run launch_agent there)")
        name = agents[0]
        client = self._launch_clients.get(name)
        if client is None:
            client = self._launch_clients[name] = self.create_client(Launch, f"/{name}/launch", qos_profile=SERVICE_QOS)
        if not client.service_is_ready():
            raise LaunchError(f"launch agent {name} on {machine!r} does not answer")
        key = launch_key(record)
        future = client.call_async(Launch.Request(name=key, argv=list(record.launch_command)))

        def done(f) -> None:
            answer = f.result() if f.exception() is None else None
            if answer is not None and answer.ok:
                self.get_logger().info(f"{key}: started by {name} on {machine!r} (pid {answer.pid} there)")
                return
            why = answer.reason if answer is not None else repr(f.exception())
            reason = f"launch agent {name} on {machine!r}: {why}"
            self._emit(self._registry.launch_exited(key, -1, now=time.monotonic(), reason=reason))

        future.add_done_callback(done)

    def _on_tick(self) -> None:
        try:
            now = time.monotonic()
            # A tick much later than due means this process was not scheduled (a loaded machine):
            # renewals are waiting unread, so nobody has missed a lease by that much.
            late = now - self._last_tick - self._cfg.tick_period
            self._last_tick = now
            if late > STALL:
                self._registry.pause(late)
                self.stalls += 1
                self.get_logger().warning(
                    f"the ComMAg was not scheduled for {late:.2f} s: leases extended by as much",
                    throttle_duration_sec=5.0,
                )
            events = []
            for name, code in self._launcher.poll():
                events += self._registry.launch_exited(name, code, now=now)
            events += self._registry.tick(now)
            self._emit(events)
            if now - self._last_diag >= self._cfg.diagnostics_period:
                self._last_diag = now
                self._publish_diagnostics()
        except Exception as exc:  # keep supervising whatever one tick hit
            self.get_logger().error(f"tick failed: {exc!r}", throttle_duration_sec=5.0)

    def _emit(self, events: list[Event]) -> None:
        stamp = self.get_clock().now().to_msg()
        for event in events:
            if event.kind is EventKind.RENEWED and event.reason == "renewed" and not self._cfg.publish_renewals:
                continue
            if event.kind is not EventKind.RENEWED:
                self.get_logger().info(f"{event.record.name}: {event.kind.name.lower()} ({event.reason})")
            self._events_pub.publish(event_to_msg(event, stamp))
        if self._registry.changed:
            self._save()
            self._publish_snapshot()

    def _save(self) -> None:
        """Hand the registry to the saver thread (a slow disk must not delay renewals past their lease)."""
        if self._registry is None or self._store_path is None:
            return
        if self._saver is None:
            self._saver = store.Saver(self._store_path, on_error=self._on_save_error)
        self._saver.save(self._registry.dump())
        self._registry.changed = False

    def _on_save_error(self, exc: OSError) -> None:
        self.get_logger().error(f"cannot save the registry: {exc}", throttle_duration_sec=10.0)

    def stop_launched(self) -> None:
        """Kill what this ComMAg launched, if configured to (a team that ends with its ComMAg)."""
        cfg = getattr(self, "_cfg", None)  # set by on_configure
        if self._launcher is not None and cfg is not None and cfg.stop_launched_on_exit:
            self._launcher.stop_all()

    def close_store(self) -> None:
        """Write the last state and stop the saver (at exit)."""
        self._save()
        if self._saver is not None:
            self._saver.close()
            self._saver = None

    def _publish_snapshot(self) -> None:
        msg = RegistryMsg(stamp=self.get_clock().now().to_msg())
        msg.records = [to_msg(e.record, e) for e in self._registry.directory.entries()]
        self._snapshot_pub.publish(msg)

    def _publish_diagnostics(self) -> None:
        entries = self._registry.directory.entries()
        array = DiagnosticArray()
        array.header.stamp = self.get_clock().now().to_msg()
        counts = {state: 0 for state in State}
        for entry in entries:
            counts[entry.state] += 1
            rec = entry.record
            array.status.append(
                DiagnosticStatus(
                    level=_LEVEL[entry.state],
                    name=f"commag: {rec.name}",
                    message=entry.state.value,
                    hardware_id=rec.address or rec.transport.value,
                    values=[
                        KeyValue(key="service_class", value=rec.service_class),
                        KeyValue(key="team", value=rec.team),
                        KeyValue(key="player_number", value=str(rec.player_number)),
                        KeyValue(key="failures", value=str(entry.failures)),
                        KeyValue(key="launches", value=str(entry.launches)),
                    ],
                )
            )
        worst = DiagnosticStatus.WARN if counts[State.SUSPECT] or counts[State.RELAUNCHING] else DiagnosticStatus.OK
        array.status.insert(
            0,
            DiagnosticStatus(
                level=worst,
                name="commag",
                message=", ".join(f"{n} {s.value}" for s, n in counts.items()),
                values=[KeyValue(key=s.value, value=str(n)) for s, n in counts.items()],
            ),
        )
        self._diag_pub.publish(array)


def _started() -> CommagNode:
    node = CommagNode()
    if node.get_parameter("autostart").value:
        node.trigger_configure()
        node.trigger_activate()
    return node


def _stopped(node: CommagNode) -> None:
    node.close_store()
    node.stop_launched()


def main(args: list[str] | None = None) -> int:
    """Entry point of ``ros2 run cf_commag commag``."""
    return run(_started, on_exit=_stopped, args=args)


if __name__ == "__main__":
    sys.exit(main())
