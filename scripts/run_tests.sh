#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Set up .venv/ if needed, then run every test (unit, node, multi-process, lint) from the
# repository root. Arguments go to pytest (e.g. -q, -k ik, test/model/test_geometry.py); exits with
# pytest's exit code.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"${root}/scripts/setup_venv.sh"
# shellcheck source=scripts/ros_env.sh
source "${root}/scripts/ros_env.sh"
cd "${root}"
# Without path arguments pytest runs test/ (testpaths in pytest.ini).
exec "${root}/.venv/bin/python" -m pytest "$@"
