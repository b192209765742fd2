"""mazesim over ROS 1: the report's custom ROS controller (chapter 3), in lockstep.

An optional part of mazesim: importing it, or :mod:`mazesim`, never needs ROS. The nodes import
``rospy`` only when they start, and say how to install it if it is missing.

- :mod:`mazesim.ros.bridge`: the bridge node, a simulator publishing ``sensors``, ``sensor_data``,
  ``pose`` and ``/clock`` and stepping on ``motor``, ``action`` or ``cmd_vel`` commands, in
  ``lockstep`` or ``realtime`` mode.
- :mod:`mazesim.ros.standard`: the standard messages the bridge publishes beside the report's
  (``sensor_msgs/Range`` per distance sensor, ``nav_msgs/Odometry``, tf) and the
  ``geometry_msgs/Twist`` it takes on ``cmd_vel``.
- :mod:`mazesim.ros.avoid_collision`: the avoid-collision controller node (Listing 3.2).
- :mod:`mazesim.ros.perform_learning`: the perform-learning node (Alg. 5), the hierarchical policy
  of :mod:`mazesim.learn` answering ``sensor_data`` with ``action`` codes.
- :mod:`mazesim.ros.demo`: ``mazesim ros demo``, bridge and a controller node on a private master,
  recorded in a bag.
- :mod:`mazesim.ros.topics`: the topics and their layouts (the codes of the ``action`` topic and
  their wheel speeds are :mod:`mazesim.actions`).
- :mod:`mazesim.ros.local_master`: a private master on a free loopback port with the processes
  started against it, for demos, benchmarks and tests.

The nodes run with ``roslaunch`` (the ROS package ``ros/mazesim_ros`` of the repository, whose
``view.launch`` also opens rviz) or as
``mazesim ros bridge``, ``mazesim ros avoid-collision`` and ``mazesim ros perform-learning``.
"""

from __future__ import annotations

__all__: list[str] = []
