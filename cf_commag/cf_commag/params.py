"""Every node's parameters, one way: a frozen, validated pydantic model.

Each field is declared as a ROS parameter with the field's description (so ``ros2 param
describe`` tells what it is) and its default; the node reads them back once, validated:

    class DecisionParams(ComponentParams):
        team: str = Field("blue", description="team name, as the components register it")

    params = DecisionParams.declare_and_read(node)     # ValueError naming the bad parameter

Tuples become string arrays (an empty one is declared as ``[""]``: ROS cannot infer the type
of an empty list). ``ComponentParams`` holds what every component has.
"""

from __future__ import annotations

from typing import Self

from pydantic import BaseModel, ConfigDict, Field, ValidationError
from rcl_interfaces.msg import ParameterDescriptor

from .given_parameters import parameters_for


class NodeParams(BaseModel):
    """A node's parameters; subclasses add fields, each with a description."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    @classmethod
    def declare(cls, node) -> None:
        for name, info in cls.model_fields.items():
            default = info.default
            if isinstance(default, tuple):
                default = list(default) or [""]
            node.declare_parameter(name, default, ParameterDescriptor(description=info.description or ""))

    @classmethod
    def read(cls, node) -> Self:
        """The declared parameters' values, validated; ValueError saying which is wrong and why."""
        values = {}
        for name, info in cls.model_fields.items():
            value = node.get_parameter(name).value
            if isinstance(info.default, tuple):
                value = tuple(v for v in (value or []) if v)
            values[name] = value
        try:
            return cls(**values)
        except ValidationError as exc:
            problems = "; ".join(f"{'.'.join(map(str, e['loc']))}: {e['msg']}" for e in exc.errors())
            raise ValueError(f"invalid parameters: {problems}") from None

    @classmethod
    def declare_and_read(cls, node) -> Self:
        cls.declare(node)
        return cls.read(node)

    @classmethod
    def given(cls, node_kwargs: dict) -> dict:
        """The values a node made with ``node_kwargs`` will get, before it exists (to name it)."""
        return parameters_for({n: f.default for n, f in cls.model_fields.items()}, node_kwargs)


class ComponentParams(NodeParams):
    """What every component (an agent registered with the ComMAg) has."""

    commag: str = Field("/commag", description="the ComMAg's node name")
    lease: float = Field(1.0, gt=0, le=300, description="lease period (s) with the ComMAg")
    name: str = Field("", description="agent name (empty: the component's default, e.g. <team>_<number>_<role>)")
    relaunch: bool = Field(
        True,
        description="register the command that starts this process again, so the ComMAg relaunches it; "
        "false when something else restarts it (launch's respawn) or nothing may",
    )

    def launch_command(self, command: list[str]) -> list[str]:
        """The launch command to register: ``command``, or none if this component is not to be relaunched."""
        return command if self.relaunch else []
