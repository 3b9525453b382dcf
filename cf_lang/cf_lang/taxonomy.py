"""The taxonomy of soccer services (paper, Fig. 3): who can serve what.

A provider registers one service class. A request names a class too. The
``Direction`` of a lookup says which providers count as a match:

- ``GENERAL`` (the default): the requested class and its ancestors. A
  provider of a more general class can serve a more specific request: an
  ``Action`` provider can execute a ``Dribble``.
- ``SPECIFIC``: the requested class and its descendants: asking for
  ``Perception`` also finds a ``BallPerception`` provider.
- ``BOTH``: either of the above. ``EXACT``: only the class itself.

Matches rank by taxonomy distance (exact first); at equal distance a more
specific provider ranks before a more general one.
"""

from __future__ import annotations

from enum import IntEnum

from .errors import LanguageError


class TaxonomyError(LanguageError):
    """A service class that the taxonomy does not know."""


class Direction(IntEnum):
    """Which way a lookup searches the taxonomy (same numbers as Lookup.srv)."""

    GENERAL = 0
    SPECIFIC = 1
    BOTH = 2
    EXACT = 3


# child -> parent; the root has none.
_TREE: dict[str, str | None] = {
    "Service": None,
    # What a player senses and knows.
    "Perception": "Service",
    "WorldModel": "Perception",
    "Localisation": "WorldModel",
    "BallPerception": "WorldModel",
    "PlayerPerception": "WorldModel",
    "GamePerception": "WorldModel",
    "Hearing": "Perception",
    # What a player does.
    "Action": "Service",
    "BallAction": "Action",
    "Kick": "BallAction",
    "Shoot": "Kick",
    "Pass": "Kick",
    "Dribble": "BallAction",
    "Intercept": "BallAction",
    "Tackle": "BallAction",
    "Catch": "BallAction",
    "Movement": "Action",
    "MoveTo": "Movement",
    "Dash": "Movement",
    "Turn": "Movement",
    "HeadMovement": "Action",
    "Communication": "Action",
    # What a player decides.
    "Decision": "Service",
    "PlayerDecision": "Decision",
    "TeamCoordination": "Decision",
    "Coaching": "Decision",
    # Infrastructure a team runs beside its players.
    "Backend": "Service",
    "Simulator": "Backend",
    "RobotDriver": "Backend",
    "Launcher": "Backend",  # a launch agent: starts components on its host for the ComMAg
    "Monitoring": "Service",
}


class Taxonomy:
    """A tree of service classes with ancestor/descendant queries and matching."""

    def __init__(self, parent_of: dict[str, str | None]):
        self._parent = dict(parent_of)
        self._children: dict[str, list[str]] = {name: [] for name in self._parent}
        for name, parent in self._parent.items():
            if parent is not None:
                if parent not in self._parent:
                    raise TaxonomyError(f"{name}: unknown parent {parent}")
                self._children[parent].append(name)
        self._ancestors = {name: self._walk_up(name) for name in self._parent}

    def _walk_up(self, name: str) -> tuple[str, ...]:
        chain = []
        parent = self._parent[name]
        while parent is not None:
            chain.append(parent)
            parent = self._parent[parent]
        return tuple(chain)

    @property
    def classes(self) -> tuple[str, ...]:
        """Every class, parents before children."""
        return tuple(self._parent)

    def __contains__(self, name: object) -> bool:
        return name in self._parent

    def check(self, name: str) -> str:
        """Return name if it is a known class, else raise TaxonomyError."""
        if name not in self._parent:
            raise TaxonomyError(f"unknown service class {name!r}; known: {', '.join(self._parent)}")
        return name

    def parent(self, name: str) -> str | None:
        return self._parent[self.check(name)]

    def children(self, name: str) -> tuple[str, ...]:
        return tuple(self._children[self.check(name)])

    def ancestors(self, name: str) -> tuple[str, ...]:
        """Ancestors, nearest first."""
        return self._ancestors[self.check(name)]

    def descendants(self, name: str) -> tuple[str, ...]:
        """Descendants, breadth first."""
        out: list[str] = []
        queue = list(self.children(name))
        while queue:
            cls = queue.pop(0)
            out.append(cls)
            queue.extend(self._children[cls])
        return tuple(out)

    def depth(self, name: str) -> int:
        return len(self.ancestors(name))

    def is_a(self, name: str, ancestor: str) -> bool:
        """True if name is ancestor or one of its descendants."""
        return name == ancestor or ancestor in self.ancestors(name)

    def match_distance(self, requested: str, provider: str, direction: Direction = Direction.GENERAL) -> int | None:
        """How far provider is from requested, or None if it does not match.

        Negative distances are more specific providers, positive more general
        ones; sort by ``(abs(d), d)`` for the documented ranking.
        """
        self.check(requested)
        self.check(provider)
        if provider == requested:
            return 0
        if direction in (Direction.GENERAL, Direction.BOTH):
            up = self._ancestors[requested]
            if provider in up:
                return up.index(provider) + 1
        if direction in (Direction.SPECIFIC, Direction.BOTH):
            up = self._ancestors[provider]
            if requested in up:
                return -(up.index(requested) + 1)
        return None

    def can_serve(self, provider: str, requested: str) -> bool:
        """The paper's rule: a provider serves its own class and everything below it."""
        return self.match_distance(requested, provider, Direction.GENERAL) is not None


SERVICES = Taxonomy(_TREE)
