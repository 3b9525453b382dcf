"""Where things are, with uncertainty (paper, Fig. 6). Metres, radians, seconds.

Field frame: origin at the centre spot, x towards the opponents' goal, y to
the left, angles counter-clockwise from +x in (-pi, pi].
"""

from __future__ import annotations

import math

from pydantic import Field

from .base import Concept

Sigma = Field(default=None, ge=0.0, description="standard deviation (same unit as the value)")


class AbsolutePositioning(Concept):
    """A pose in the field frame; each part may carry a standard deviation."""

    x: float = Field(ge=-70.0, le=70.0)
    y: float = Field(ge=-50.0, le=50.0)
    yaw: float | None = Field(default=None, ge=-2 * math.pi, le=2 * math.pi)
    sigma_x: float | None = Sigma
    sigma_y: float | None = Sigma
    sigma_yaw: float | None = Sigma


class RelativePositioning(Concept):
    """Distance and direction from the observer's body (direction CCW, radians)."""

    distance: float = Field(ge=0.0, le=200.0)
    direction: float = Field(ge=-2 * math.pi, le=2 * math.pi)
    sigma_distance: float | None = Sigma
    sigma_direction: float | None = Sigma


class Velocity(Concept):
    """Velocity in the field frame, metres per second."""

    vx: float = Field(ge=-50.0, le=50.0)
    vy: float = Field(ge=-50.0, le=50.0)
    sigma_vx: float | None = Sigma
    sigma_vy: float | None = Sigma
