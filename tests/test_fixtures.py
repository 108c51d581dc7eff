"""Negative fixtures: files a test loads expecting them to be refused are the test's
point, not findings (``extract.python.fixtures``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from conftest import write, write_package

from roslint_names.extract.python.fixtures import rejected_fixtures

# ros_comm's tools/roslaunch/test/unit/test_xmlloader.py, reduced: the three ways it and
# other ROS tests load a file expecting the loader to refuse it.
XMLLOADER_TEST = """import os
import unittest

import roslaunch.xmlloader
from roslaunch.xmlloader import XmlParseException


class TestXmlLoader(unittest.TestCase):
    def setUp(self):
        self.xml_dir = os.path.join(os.path.dirname(__file__), "..", "xml")

    def _load(self, test_file):
        loader = roslaunch.xmlloader.XmlLoader()
        loader.load(os.path.join(self.xml_dir, test_file), RosLaunchMock())

    def test_params(self):
        self._load("test-params-valid.xml")

    def test_node_invalid(self):
        tests = ['test-node-invalid-type.xml',
                 'test-node-invalid-name-2.xml',
                 ]
        loader = roslaunch.xmlloader.XmlLoader()
        for filename in tests:
            filename = os.path.join(self.xml_dir, filename)
            try:
                self.assert_(os.path.exists(filename))
                loader.load(filename, RosLaunchMock())
                self.fail("xmlloader did not throw an xmlparseexception for [%s]" % filename)
            except roslaunch.xmlloader.XmlParseException:
                pass

    def test_remap_invalid(self):
        with self.assertRaises(XmlParseException):
            self._load("test-remap-invalid-name-to.xml")
        self.assertRaises(XmlParseException, self._load, "test-machine-invalid.xml")
"""
NODE_INVALID_NAME = """<launch>
  <node pkg="package" type="name_test_invalid_value" name="ns/foo" />
</launch>
"""
REMAP_INVALID_NAME = """<launch>
  <remap from="from" to="to something" />
</launch>
"""
# Loaded to succeed: its mistake is real, the test would fail on it.
PARAMS_VALID = """<launch>
  <param name="robot description" value="urdf" />
</launch>
"""


def test_files_a_test_expects_to_be_refused_are_not_reported(run_cli: Any, tmp_path: Path) -> None:
    """Before, each of the two refused files was an RN101 (ros_comm: 4 such findings)."""
    package = tmp_path / "tools/roslaunch"
    write_package(package, 1, "roslaunch")
    write(package, "test/unit/test_xmlloader.py", XMLLOADER_TEST)
    write(package, "test/xml/test-node-invalid-name-2.xml", NODE_INVALID_NAME)
    write(package, "test/xml/test-remap-invalid-name-to.xml", REMAP_INVALID_NAME)
    write(package, "test/xml/test-params-valid.xml", PARAMS_VALID)
    # The same file name in another package is that package's own launch file.
    write_package(tmp_path / "robot_bringup", 1, "robot_bringup")
    write(tmp_path, "robot_bringup/launch/test-node-invalid-name-2.xml", NODE_INVALID_NAME)
    result = run_cli(["check", "--format", "json", "."], tmp_path)
    found = [(f["path"], f["code"]) for f in result.findings()]
    assert found == [
        ("robot_bringup/launch/test-node-invalid-name-2.xml", "RN101"),
        ("tools/roslaunch/test/xml/test-params-valid.xml", "RN101"),
    ]


def test_the_fixture_names_of_each_expected_failure_form() -> None:
    assert rejected_fixtures(XMLLOADER_TEST.encode()) == (
        "test-machine-invalid.xml",
        "test-node-invalid-name-2.xml",
        "test-node-invalid-type.xml",
        "test-remap-invalid-name-to.xml",
    )
    pytest_form = b"""import pytest
from launch.frontend import Parser

def test_bad_launch_file(tmp_path):
    good = tmp_path / "good.launch.xml"
    with pytest.raises(ValueError):
        Parser.load(os.path.join(HERE, "launch", "bad_substitution.launch.xml"))
"""
    assert rejected_fixtures(pytest_form) == ("bad_substitution.launch.xml",)
    # Loaded to succeed, or no failure expected anywhere: nothing.
    assert rejected_fixtures(b'def test_x():\n    load("robot.launch")\n') == ()
    assert rejected_fixtures(b"def test_x(:\n    self.fail('a.launch')\n") == ()
