# shellcheck shell=bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Source this file (`source scripts/ros_env.sh`) to talk ROS 2 the way the scripts and tests do:
# - ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST, always: DDS traffic stays on this machine.
# - ROS_LOG_DIR: the repository's .ros_log/ unless already set (keeps logs out of ~/.ros).
# - FASTRTPS_DEFAULT_PROFILES_FILE: scripts/fastdds_localhost.xml unless already set (faster
#   discovery, see the comment in that file).
# ROS_DOMAIN_ID is left alone: ramp_demo and the tests reserve a free one themselves, unless
# you set one.

_stewart_kinematics_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
export ROS_LOG_DIR="${ROS_LOG_DIR:-${_stewart_kinematics_root}/.ros_log}"
mkdir -p "${ROS_LOG_DIR}"
export FASTRTPS_DEFAULT_PROFILES_FILE="${FASTRTPS_DEFAULT_PROFILES_FILE:-${_stewart_kinematics_root}/scripts/fastdds_localhost.xml}"

unset _stewart_kinematics_root
