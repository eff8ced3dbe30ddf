#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Set up .venv/ if needed, then play the paper's Table 3 ramp through ik_node, fk_node and
# trajectory_node (see README.md). Arguments go to ramp_demo (try --help); exits with its code.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"${root}/scripts/setup_venv.sh"
# shellcheck source=scripts/ros_env.sh
source "${root}/scripts/ros_env.sh"
exec "${root}/.venv/bin/ramp_demo" "$@"
