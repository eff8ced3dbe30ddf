#!/usr/bin/env bash
# Copyright 2026 stewart_kinematics developers
# SPDX-License-Identifier: Apache-2.0
#
# Build the stand-in interface packages of test/resources/ into a venv, so that what the nodes
# speak through them is tested for real where ROS is not installed:
# - tf2_msgs (msg/TFMessage only): the nodes' /tf and /tf_static broadcasts;
# - control_msgs (action/FollowJointTrajectory, msg/JointTolerance, msg/JointComponentTolerance,
#   copied unchanged from Jazzy's): trajectory_node's follow_joint_trajectory action.
# Neither is on PyPI, but the rosidl tools are (requirements.txt pins them), and the definitions
# have the same type hashes as upstream's (test/package/test_interface_hashes.py). A ROS
# installation has the real packages; these stand-ins are never shipped (test/resources/ carries
# a COLCON_IGNORE).
#
# Usage: scripts/build_interfaces.sh [VENV]   (default: .venv/ in the repository root)
#
# Steps: rewrite the build machine's paths that the ROS wheels' CMake exports hard-code
# (/opt/python/cp3XX-cp3XX/include/python3.X and its numpy include folder) to this venv's, then
# configure, build and install each package into the venv's prefix with CMake, as colcon would
# (the venv's lib/ is on the library path that the ROS wheels' start-up hook sets).
#
# Idempotent: does nothing for a package that imports in the venv when its sources, this script
# and the Python version are unchanged since its last build (a hash in VENV/.<package>_stamp).
# Quiet: a build's output is shown only when it fails.

set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$(cd "${1:-${root}/.venv}" && pwd)"
python="${venv}/bin/python"
#: Each stand-in package, and a Python import that shows it is installed.
packages=(tf2_msgs control_msgs)
declare -A probes=(
    [tf2_msgs]='from tf2_msgs.msg import TFMessage'
    [control_msgs]='from control_msgs.action import FollowJointTrajectory'
)

fail() {
    echo "build_interfaces.sh: $*" >&2
    exit 1
}

[[ -x "${python}" ]] || fail "no venv at ${venv} (run scripts/setup_venv.sh)"
for tool in cmake make cc; do
    command -v "${tool}" >/dev/null 2>&1 \
        || fail "${tool} is needed to build the stand-in interfaces (apt-get install cmake build-essential)"
done

# Hash of everything the build of one package (its folder, $1) depends on.
build_hash() {
    "${python}" - "${BASH_SOURCE[0]}" "$1" <<'PYTHON'
import hashlib
import pathlib
import sys

digest = hashlib.sha256(sys.version.encode())
paths = [pathlib.Path(sys.argv[1])] + sorted(
    path for path in pathlib.Path(sys.argv[2]).rglob('*') if path.is_file())
for path in paths:
    digest.update(path.name.encode() + b'\0' + path.read_bytes() + b'\0')
print(digest.hexdigest())
PYTHON
}

python_include="$("${python}" -c 'import sysconfig; print(sysconfig.get_paths()["include"])')"
numpy_include="$("${python}" -c 'import numpy; print(numpy.get_include())')"
# The wheels were built in a manylinux image with Python in /opt/python/cp3XX-cp3XX (grep finds
# nothing once rewritten).
{ grep -rlE --include='*.cmake' '/opt/python/cp3[0-9]+-cp3[0-9]+/' "${venv}/share" || true; } \
    | xargs -r sed -i -E \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/lib/python3\.[0-9]+/site-packages/numpy/_core/include#${numpy_include}#g" \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/include/python3\.[0-9]+#${python_include}#g"

build_directory="$(mktemp -d)"
log="$(mktemp)"
trap 'rm -rf "${build_directory}" "${log}"' EXIT

# Build one package ($1) from test/resources/$1 into the venv, unless its stamp matches.
build_package() {
    local package="$1"
    local source_directory="${root}/test/resources/${package}"
    local stamp="${venv}/.${package}_stamp"
    if [[ -f "${stamp}" ]] && [[ "$(cat "${stamp}")" == "$(build_hash "${source_directory}")" ]] \
            && "${python}" -c "${probes[${package}]}" >/dev/null 2>&1; then
        return 0
    fi
    rm -f "${stamp}"
    local start=${SECONDS}
    if ! {
        export PATH="${venv}/bin:${PATH}" AMENT_PREFIX_PATH="${venv}" CMAKE_PREFIX_PATH="${venv}"
        cmake -S "${source_directory}" -B "${build_directory}/${package}" \
            -DCMAKE_INSTALL_PREFIX="${venv}" -DPython3_EXECUTABLE="${python}" -DBUILD_TESTING=OFF \
            && cmake --build "${build_directory}/${package}" --parallel 2 \
            && cmake --install "${build_directory}/${package}"
    } >"${log}" 2>&1; then
        cat "${log}" >&2
        fail "building ${package} failed (output above)"
    fi
    "${python}" -c "${probes[${package}]}" \
        || fail "${package} was built but does not import in ${venv}"
    build_hash "${source_directory}" >"${stamp}"
    echo "build_interfaces.sh: ${package} built into ${venv} ($((SECONDS - start)) s)"
}

for package in "${packages[@]}"; do
    build_package "${package}"
done
