"""The inbox transport: what an agent's messages travel as on DDS (no agent logic here).

- ``qos``: every QoS profile of the framework's topics and services;
- ``cdr``: a ``std_msgs/String`` sample as CDR bytes, without a message object (ROS-free);
- ``samples``: several ACL messages packed into one sample, one per line (ROS-free);
- ``outbox``: inbox topic names, the text of a sample, and the Outbox that publishes to inboxes.

Submodules are imported by name, so the ROS-free ones stay importable without rclpy.
"""
