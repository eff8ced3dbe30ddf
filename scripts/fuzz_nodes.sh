#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# The long run of the node fuzzer: set up .venv/ if needed, then fuzz every declared node as a
# process, round after round (a new seed each round), for --minutes (e.g. 10). Arguments go to
# `python -m fuzzing.node_fuzzer` (try --help): --minutes, --node NAME, --seed,
# --messages, --rate, --huge. Each failed round prints its problems, the last messages sent and
# the options that replay it; exits 1 if a round failed. Runs on its own isolated ROS domain.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"${root}/scripts/setup_venv.sh"
# shellcheck source=scripts/ros_env.sh
source "${root}/scripts/ros_env.sh"
cd "${root}"
exec "${root}/.venv/bin/python" -m fuzzing.node_fuzzer "$@"
