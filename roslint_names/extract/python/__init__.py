"""Python: rospy and rclpy names, init calls and nodes, through libcst.

``extract`` is the entry: a byte prefilter decides whether the file can hold a ROS name
before libcst is imported; ``parsed`` decodes, parses and walks what passes (``walk``,
``scope``, ``fold``, ``spans``, ``source``, ``text``) and hands rospy/rclpy code to
``code`` (whose calls ``apis`` knows) and launch descriptions to ``launch``.
"""
