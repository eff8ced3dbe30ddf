#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Set up .venv/ if needed, then run every test (unit, node, multi-process, lint) from the
# repository root. Arguments go to pytest (e.g. -q, -k ik, test/model/test_geometry.py); exits with
# pytest's exit code (the first failing phase's, for the whole suite).

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"${root}/scripts/setup_venv.sh"
# shellcheck source=scripts/ros_env.sh
source "${root}/scripts/ros_env.sh"
cd "${root}"
python="${root}/.venv/bin/python"

# The whole suite (no arguments but output flags) runs in two phases: the core and lint tiers
# (pure numpy, the linters, the documentation build: independent, no timing) on every core
# with pytest-xdist, then the node and process tiers in one process, as before, since they
# measure timing and rates that a second worker on the same cores would disturb. Any other
# arguments (paths, -m, -k, -n, ...) go to one pytest run as they are.
whole_suite=true
for argument in "$@"; do
  case "${argument}" in
    -q | -qq | -v | -vv | -ra | -rA | -rf | -x | --color=*) ;;
    *) whole_suite=false ;;
  esac
done
if [[ "${whole_suite}" != true ]]; then
  # Without path arguments pytest runs test/ (testpaths in pytest.ini).
  exec "${python}" -m pytest "$@"
fi
workers="$("${python}" -c 'import os; print(max(1, min(2, len(os.sched_getaffinity(0)))))')"
status=0
echo "run_tests.sh: core and lint tiers on ${workers} worker(s)"
"${python}" -m pytest "$@" -m 'core or lint' -n "${workers}" --dist worksteal || status=$?
echo "run_tests.sh: node and process tiers in one process"
"${python}" -m pytest "$@" -m 'node or process' || {
  code=$?
  if [[ "${status}" -eq 0 ]]; then status=${code}; fi
}
exit "${status}"
