#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Set up .venv/ if needed, add the baseline packages of benchmarks/requirements.txt (scipy,
# basic-robotics; not needed otherwise), then run benchmarks/run_benchmarks.py on an isolated
# ROS domain: it prints the tables and writes them to benchmarks/results.md. Takes about three
# minutes. With --update-docs (first argument; --update-readme is the old name of the same
# flag), scripts/update_doc_tables.py then copies the new tables into doc/benchmarks.md. Other
# arguments go to run_benchmarks.py (try --help); exits with its code.

set -euo pipefail

update_docs=false
if [[ "${1:-}" == "--update-docs" || "${1:-}" == "--update-readme" ]]; then
    update_docs=true
    shift
fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"${root}/scripts/setup_venv.sh"
log="$(mktemp)"
if ! "${root}/.venv/bin/python" -m pip --disable-pip-version-check --no-input install \
        --requirement "${root}/benchmarks/requirements.txt" >"${log}" 2>&1; then
    # basic-robotics may not install here: the benchmark reports it and goes on.
    echo "run_benchmarks.sh: baseline install failed (last lines below); going on" >&2
    tail -n 5 "${log}" >&2
    "${root}/.venv/bin/python" -m pip --disable-pip-version-check --no-input install --quiet \
        "$(grep '^scipy' "${root}/benchmarks/requirements.txt")" || true
fi
rm -f "${log}"
# shellcheck source=scripts/ros_env.sh
source "${root}/scripts/ros_env.sh"
cd "${root}"
"${root}/.venv/bin/python" -W ignore "${root}/benchmarks/run_benchmarks.py" "$@"
if [[ "${update_docs}" == true ]]; then
    "${root}/.venv/bin/python" "${root}/scripts/update_doc_tables.py"
fi
