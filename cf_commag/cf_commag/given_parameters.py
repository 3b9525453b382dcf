"""The parameter values a node will be given, read before the node exists.

A component's node is named after its agent (``blue_7_decision``), and the
agent's name comes from parameters (team, number, ...). rclpy only reads
parameters once the node is created, under its name, so this reads them the
way rcl will: ``/**`` sections of ``--params-file`` files (what ``ros2 launch``
writes), then ``-p name:=value`` (later ones win), then the constructor's
``parameter_overrides``. Sections for one node name are not read: the name is
what is being decided.
"""

from __future__ import annotations

import itertools
import re
import sys
from collections.abc import Iterable, Sequence

import yaml

_WILDCARDS = ("/**", "**")


def _ros_args(argv: Sequence[str]) -> list[str]:
    """The arguments inside ``--ros-args ... [--]`` blocks."""
    out, inside = [], False
    for arg in argv:
        if arg == "--ros-args":
            inside = True
        elif arg == "--" and inside:
            inside = False
        elif inside:
            out.append(arg)
    return out


def _from_file(path: str) -> dict[str, object]:
    try:
        with open(path, encoding="utf-8") as f:
            data = yaml.safe_load(f) or {}
    except (OSError, yaml.YAMLError):
        return {}  # rcl reports an unreadable file itself
    values: dict[str, object] = {}
    for key in _WILDCARDS:
        section = data.get(key) if isinstance(data, dict) else None
        if isinstance(section, dict) and isinstance(section.get("ros__parameters"), dict):
            values.update(section["ros__parameters"])
    return values


def given_parameters(
    argv: Sequence[str] | None = None, overrides: Iterable[object] | None = None, cli_args: Sequence[str] = ()
) -> dict[str, object]:
    """Name -> value of what the command line (``argv``, default sys.argv), ``cli_args`` and overrides set."""
    args = _ros_args(list(sys.argv if argv is None else argv)) + _ros_args(list(cli_args))
    values: dict[str, object] = {}
    for flag, value in itertools.pairwise(args):
        if flag == "--params-file":
            values.update(_from_file(value))
    for flag, value in itertools.pairwise(args):
        if flag in ("-p", "--param") and ":=" in value:
            name, _, text = value.partition(":=")
            try:
                values[name] = yaml.safe_load(text)
            except yaml.YAMLError:
                values[name] = text
    for param in overrides or ():
        values[param.name] = param.value
    return values


def node_name(text: str) -> str:
    """``text`` made a valid ROS node name (letters, digits, underscores; not starting with a digit)."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", text)
    return name if name and not name[0].isdigit() else f"n_{name}"


def parameters_for(defaults: dict[str, object], node_kwargs: dict) -> dict[str, object]:
    """``defaults`` updated with what a node constructed with ``node_kwargs`` will be given."""
    given = given_parameters(
        argv=[] if node_kwargs.get("use_global_arguments") is False else None,
        overrides=node_kwargs.get("parameter_overrides"),
        cli_args=node_kwargs.get("cli_args") or (),
    )
    return {**defaults, **{k: v for k, v in given.items() if k in defaults}}
