"""ROS 2 for mazesim, without a ROS 2 installation: the e-puck's standard topics over DDS.

The bridge (:mod:`~mazesim.ros2.bridge`) is an ordinary ROS 2 node on the wire: Cyclone DDS
(``cyclonedds``) carries ROS 2's messages as each distribution lays them out
(:mod:`~mazesim.ros2.messages`, encoded by :mod:`~mazesim.ros2.cdr`), with ROS 2's QoS
(:mod:`~mazesim.ros2.qos`) and graph information (:mod:`~mazesim.ros2.graph`), discovery limited to
this machine unless asked (:mod:`~mazesim.ros2.network`), simulation time in lockstep or
free-running (:mod:`~mazesim.ros2.clock`), the topics of :mod:`~mazesim.ros2.state`, bags
(:mod:`~mazesim.ros2.bag`), controller nodes (:mod:`~mazesim.ros2.nodes`) and a demo
(:mod:`~mazesim.ros2.demo`). It needs the extra ``mazesim[ros2]`` (``cyclonedds``, ``rosbags``);
``import mazesim`` never does, and this package imports them only when used.
"""

from mazesim.ros2._deps import require_ros2

__all__ = ["require_ros2"]
