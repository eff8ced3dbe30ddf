# Copyright 2026 stewart_kinematics developers
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""
Turns the parameter specs of :mod:`stewart_kinematics.parameters` into ROS declarations.

A node calls :func:`declare_parameters` once in its constructor. It registers the validator
before declaring, so that a bad value from a parameter file fails the declaration with the
spec's reason (the node then stops at start-up), and a bad value set at run time is rejected
with that reason while the old value stays.
"""

from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.parameter import Parameter

from stewart_kinematics import parameters

_ROS_TYPES = {
    parameters.BOOL: Parameter.Type.BOOL,
    parameters.INTEGER: Parameter.Type.INTEGER,
    parameters.DOUBLE: Parameter.Type.DOUBLE,
    parameters.STRING: Parameter.Type.STRING,
    parameters.DOUBLE_ARRAY: Parameter.Type.DOUBLE_ARRAY,
    parameters.STRING_ARRAY: Parameter.Type.STRING_ARRAY,
}


def descriptor(spec: parameters.ParameterSpec) -> ParameterDescriptor:
    """ROS descriptor of a spec: description with unit, allowed values, read-only flag."""
    description = spec.description
    if spec.constraints:
        description += f' (allowed: {spec.constraints})'
    return ParameterDescriptor(
        name=spec.name, type=_ROS_TYPES[spec.value_type].value, description=description,
        read_only=spec.read_only)


def declare_parameters(node, specs, on_change=None, check=None) -> dict:
    """
    Declare ``specs`` on ``node`` with validation, and return their values.

    :param node: an ``rclpy.node.Node``.
    :param specs: the :class:`~stewart_kinematics.parameters.ParameterSpec` to declare.
    :param on_change: called as ``on_change(name, value)`` after a run-time change of one of
        them has been accepted.
    :param check: called at run time as ``check(values)`` with every value of ``specs`` as it
        would be after a change; returns ``''`` to accept it, else the reason to refuse it (for
        rules between parameters, such as distinct frame names).
    :returns: parameter name -> value, as set by parameter files, overrides or defaults.
    :raises rclpy.exceptions.ParameterException: if a value has the wrong type or is not
        allowed; the message gives the spec's reason.
    :raises ValueError: if a required parameter is not set, or a parameter file or override
        names a parameter that no node of the package declares.
    """
    by_name = {spec.name: spec for spec in specs}
    # rclpy ignores overrides nobody declares: a misspelt name would silently keep a default.
    parameters.check_known_names(
        [name for name in node._parameter_overrides
         if not (node.has_parameter(name) or name.startswith('qos_overrides.'))],
        f'the parameters given to {node.get_fully_qualified_name()}')

    def validate(parameters):
        for parameter in parameters:
            spec = by_name.get(parameter.name)
            if spec is None or parameter.type_ == Parameter.Type.NOT_SET:
                # Not ours, or a required parameter nobody set: reported after declaring.
                continue
            reason = spec.check(parameter.value)
            if reason:
                return SetParametersResult(successful=False, reason=reason)
        if check is not None and all(node.has_parameter(name) for name in by_name):
            values = {name: node.get_parameter(name).value for name in by_name}
            values.update({parameter.name: parameter.value for parameter in parameters
                           if parameter.name in by_name})
            reason = check(values)
            if reason:
                return SetParametersResult(successful=False, reason=reason)
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(validate)
    for spec in specs:
        default = _ROS_TYPES[spec.value_type] if spec.default is None else spec.default
        node.declare_parameter(spec.name, default, descriptor(spec))

    if on_change is not None:
        def apply(parameters):
            for parameter in parameters:
                if parameter.name in by_name:
                    on_change(parameter.name, parameter.value)
        node.add_post_set_parameters_callback(apply)
    values = {spec.name: node.get_parameter_or(spec.name).value for spec in specs}
    # A required parameter that no file set was never validated: report it here.
    parameters.check_values(specs, values)
    return values


def declare_settings(node, settings_class, on_change=None, check=None):
    """
    Declare a node's parameters (:func:`declare_parameters`) and return them as its settings.

    :param settings_class: the node's :class:`~stewart_kinematics.parameters.NodeSettings`
        subclass, such as ``IkNodeSettings``: its specs are declared.
    :returns: an object of ``settings_class`` holding the values the node starts with.
    """
    values = declare_parameters(node, settings_class.specs(), on_change=on_change, check=check)
    return settings_class.from_values(values)
