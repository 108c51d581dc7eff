"""C++: roscpp and rclcpp names, init calls and handles, from tree-sitter-cpp's tree.

``extract`` is the entry (a byte prefilter, then one parse); ``source`` wraps the tree,
``types``, ``objects``, ``handles`` and ``values`` follow declarations and constants,
``apis`` knows the ROS calls, ``sites`` turns calls into name uses, ``events`` orders
init and handles (RN301), ``expected`` finds code a test expects to fail.
"""
