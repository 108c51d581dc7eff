from setuptools import find_packages, setup

package_name = "ament_roslint_names"

setup(
    name=package_name,
    version="0.1.0",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/" + package_name, ["package.xml"]),
        ("share/ament_index/resource_index/packages", ["resource/" + package_name]),
    ],
    install_requires=["setuptools", "roslint-names"],
    zip_safe=False,
    description="Check the ROS names of a package with roslint-names (ament_lint entry point).",
    license="Apache License, Version 2.0",
    entry_points={"console_scripts": ["ament_roslint_names = ament_roslint_names.main:main"]},
)
