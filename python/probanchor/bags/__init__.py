"""RGB-D recordings in ROS bags, read and written with ``rosbags`` (no ROS installation).

    from probanchor.bags import BagTopics, read_bag, write_bag
    for frame in read_bag("run.mcap"):          # rgbd.RGBDFrame, at the bag's stamps
        ...
    write_bag("out.mcap", frames)               # the simulator's frames and their ground truth

Formats: ROS 1 (``.bag``) and ROS 2 (``.db3``, ``.mcap``, or a rosbag2 directory). Colour and
depth are ``sensor_msgs/Image`` (rgb8, bgr8, rgba8, bgra8; depth 16UC1 millimetres or 32FC1
metres), the intrinsics ``sensor_msgs/CameraInfo``, the camera pose ``/tf`` and
``/tf_static`` (or an extrinsic given by the caller). A bad bag is a :class:`BagError` naming
the file and the cause (a missing topic lists the bag's topics).
"""

from probanchor.bags.read import BagError, BagTopics, bag_topics, read_bag
from probanchor.bags.write import write_bag

__all__ = ["BagError", "BagTopics", "bag_topics", "read_bag", "write_bag"]
