"""The embedded 2D simulator: its physics and referee, its node, and the nodes of each player's components on it."""
