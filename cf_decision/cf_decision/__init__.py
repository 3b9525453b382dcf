"""cf_decision: the league-independent decision component (policy.py, roles.py ROS-free; decision_node.py)."""
