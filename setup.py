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

from glob import glob

from setuptools import find_packages, setup

package_name = 'stewart_kinematics'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test', 'test.*', 'fuzzing', 'fuzzing.*']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/config',
         sorted(glob('config/*.yaml')) + sorted(glob('config/*.rviz'))),
        # Examples for ros2_control (doc/how-to/joint_trajectory_controller.md).
        ('share/' + package_name + '/config/ros2_control', sorted(glob('config/ros2_control/*'))),
        # Motion cueing per vehicle (doc/how-to/simulator.md).
        ('share/' + package_name + '/config/cueing_presets',
         sorted(glob('config/cueing_presets/*.yaml'))),
        ('share/' + package_name + '/launch', sorted(glob('launch/*.py'))),
    ],
    install_requires=['setuptools', 'numpy', 'pyyaml', 'scipy', 'toppra', 'ruckig', 'daqp'],
    zip_safe=True,
    maintainer='stewart_kinematics developers',
    maintainer_email='maintainer@example.com',
    description=(
        'Inverse and forward kinematics of a 6-6 Gough-Stewart platform (hexapod), '
        'with ROS 2 nodes'),
    license='Apache-2.0',
    # matplotlib draws the figures of ramp_demo, stewart_cueing and stewart_forces only
    # (tools/); mcap reads stewart_cueing's recorded input.
    extras_require={'demo': ['matplotlib', 'rosbags', 'mcap', 'mcap-ros2-support'],
                    'test': ['pytest', 'hypothesis']},
    entry_points={
        'console_scripts': [
            'ik_node = stewart_kinematics.ros.ik_node:main',
            'fk_node = stewart_kinematics.ros.fk_node:main',
            'trajectory_node = stewart_kinematics.ros.trajectory_node:main',
            'stewart_platform = stewart_kinematics.ros.stewart_platform:main',
            'ramp_demo = stewart_kinematics.tools.ramp_demo:main',
            'stewart_calibrate = stewart_kinematics.tools.calibrate:main',
            'stewart_workspace = stewart_kinematics.tools.workspace_report:main',
            'stewart_geometry = stewart_kinematics.tools.geometry_report:main',
            'stewart_cueing = stewart_kinematics.tools.cueing_report:main',
            'stewart_forces = stewart_kinematics.tools.forces_report:main',
            'stewart_payload = stewart_kinematics.tools.payload:main',
            'motion_cueing_node = stewart_kinematics.ros.motion_cueing_node:main',
            'mock_platform = stewart_kinematics.ros.mock_platform:main',
            'telemetry_bridge = stewart_kinematics.ros.telemetry_bridge:main',
            'telemetry_sender = stewart_kinematics.tools.telemetry_sender:main',
        ],
    },
)
