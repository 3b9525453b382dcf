"""cf_decision: the league-independent decision component (ROS-free policy modules; decision_node.py)."""
