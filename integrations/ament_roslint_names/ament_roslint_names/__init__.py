"""The ament_lint entry point of roslint-names (``ament_roslint_names``)."""
