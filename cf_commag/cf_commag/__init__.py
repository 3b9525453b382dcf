"""cf_commag: the ComMAg lifecycle node, the TCP socket gateway and the agent runtime (client.py)."""
