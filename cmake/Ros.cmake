# ROS 1: not built yet.
set(LCCP_HAVE_ROS OFF)
