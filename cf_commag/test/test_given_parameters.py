"""Reading the parameters a node will be given before it exists (to name it after its agent)."""

from __future__ import annotations

from rclpy.parameter import Parameter

from cf_commag.given_parameters import given_parameters, node_name, parameters_for


def test_command_line_params_files_and_overrides_in_rcls_order(tmp_path):
    params = tmp_path / "p.yaml"
    params.write_text(
        "/**:\n  ros__parameters:\n    team: red\n    number: 4\nother_node:\n  ros__parameters:\n    team: nobody\n"
    )
    argv = ["prog", "--ros-args", "--params-file", str(params), "-p", "number:=7", "-p", "standby:=true", "--", "x"]
    assert given_parameters(argv) == {"team": "red", "number": 7, "standby": True}
    # -p wins over the file, whatever the order; a later -p wins over an earlier one
    argv = ["prog", "--ros-args", "-p", "number:=7", "--params-file", str(params), "-p", "number:=8"]
    assert given_parameters(argv)["number"] == 8
    assert given_parameters(["prog", "-p", "number:=7"]) == {}  # outside --ros-args: not ROS's
    assert given_parameters([], overrides=[Parameter("team", value="blue")]) == {"team": "blue"}
    assert given_parameters(["prog", "--ros-args", "--params-file", str(tmp_path / "missing.yaml")]) == {}


def test_parameters_for_a_node_keep_only_its_own():
    defaults = {"team": "blue", "number": 1}
    kwargs = {"cli_args": ["--ros-args", "-p", "number:=9", "-p", "unrelated:=1"], "use_global_arguments": False}
    assert parameters_for(defaults, kwargs) == {"team": "blue", "number": 9}


def test_node_names_are_made_valid():
    assert node_name("HELIOS-base_3_rcss_player") == "HELIOS_base_3_rcss_player"
    assert node_name("7up") == "n_7up"
