"""The rcssserver back-end: the real RoboCup 2D server's protocol, a player's belief and session, the adapter node, the team."""
