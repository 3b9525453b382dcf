"""Build script of the cf_commag ROS 2 package."""

from glob import glob

from setuptools import find_packages, setup

PACKAGE = "cf_commag"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(exclude=["test"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/config", glob("config/*")),
        (f"share/{PACKAGE}/launch", glob("launch/*.py")),
    ],
    install_requires=["setuptools"],
    extras_require={"test": ["pytest"]},
    zip_safe=True,
    maintainer="Common Framework maintainers",
    maintainer_email="maintainers@commonframework.org",
    description="The ComMAg lifecycle node, the TCP socket gateway and the agent runtime.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "commag = cf_commag.commag_node:main",
            "gateway = cf_commag.gateway_node:main",
            "demo_component = cf_commag.demo_component:main",
            "supervise = cf_commag.respawn:main",
            "launch_agent = cf_commag.launch_agent:main",
        ]
    },
)
