"""Build script of the cf_sim_backend ROS 2 package."""

from glob import glob

from setuptools import find_packages, setup

PACKAGE = "cf_sim_backend"

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
    description="The embedded 2D soccer simulator and each player's perception and action components.",
    license="Apache-2.0",
    entry_points={
        "console_scripts": [
            "sim = cf_sim_backend.embedded.sim_node:main",
            "perception = cf_sim_backend.embedded.perception_node:main",
            "action = cf_sim_backend.embedded.action_node:main",
            "players = cf_sim_backend.embedded.players:main",
            "rcss_player = cf_sim_backend.rcss.player_node:main",
            "rcss_team = cf_sim_backend.rcss.team:main",
            "rcss_coach = cf_sim_backend.rcss.coach:main",
        ]
    },
)
