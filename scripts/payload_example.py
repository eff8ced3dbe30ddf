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
The payload identification example of doc/how-to/identify_payload.md: synthetic force readings.

The paper's platform with the example masses (config/example_masses.yaml: an 8 kg platform,
legs of 1.5 kg and 0.5 kg) carries a payload of 20 kg whose centre of mass is at (0.01, -0.02,
0.05) m in the platform frame; the parameter files believe it at (0, 0, 0.375) m. Its leg
forces at the poses of a CSV (as ``stewart_payload --propose`` writes them) are computed with
the package's inverse dynamics, and Gaussian noise of 1 N (seeded: the same file every time)
is added to each.

``python scripts/payload_example.py POSES_CSV MEASUREMENTS_CSV`` writes the measurements;
``python scripts/payload_example.py --check PAYLOAD_YAML`` prints how far an identified
payload is from the true one.
"""

import argparse
from dataclasses import replace
from pathlib import Path
import sys

import numpy as np

from stewart_kinematics import leg_forces, load_geometry, RigidBody
from stewart_kinematics.analysis.calibration_files import load_columns
from stewart_kinematics.analysis.payload_identification import FORCE_COLUMNS, POSE_COLUMNS

SEED = 2026
NOISE = 1.0
TRUE_PAYLOAD = RigidBody(20.0, [0.01, -0.02, 0.05], name='payload')
CONFIG = Path(__file__).resolve().parents[1] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'example_masses.yaml')]


def measure(poses_path: Path, output: Path) -> None:
    """Write the forces of the true payload at the poses of ``poses_path``, with noise."""
    poses = load_columns(poses_path, POSE_COLUMNS)[1]
    geometry = load_geometry(FILES)
    masses = replace(geometry.mass_properties, payload=TRUE_PAYLOAD)
    forces = leg_forces(geometry, poses, mass_properties=masses)
    forces = forces + np.random.default_rng(SEED).normal(0.0, NOISE, forces.shape)
    lines = [f'# {len(poses)} static poses of a synthetic payload, forces with {NOISE:g} N '
             'noise (scripts/payload_example.py)', ','.join(POSE_COLUMNS + FORCE_COLUMNS)]
    lines += [','.join(repr(float(value)) for value in row) for row in np.hstack([poses,
                                                                                 forces])]
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text('\n'.join(lines) + '\n', encoding='utf-8')
    print(f'wrote {output}: {len(poses)} poses')


def check(payload_file: Path) -> None:
    """Print the identified payload's errors from the truth (the file layered as nodes do)."""
    payload = load_geometry(FILES + [payload_file]).mass_properties.payload
    error = np.subtract(payload.center_of_mass, TRUE_PAYLOAD.center_of_mass) * 1e3
    print(f'true payload: {TRUE_PAYLOAD.mass:g} kg at '
          f'{np.multiply(TRUE_PAYLOAD.center_of_mass, 1e3).tolist()} mm')
    print(f'mass error: {payload.mass - TRUE_PAYLOAD.mass:+.3f} kg')
    print('centre of mass error (mm): ' + ', '.join(f'{value:+.2f}' for value in error))


def main(argv=None) -> int:
    """Write the synthetic measurements, or check an identified payload."""
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument('poses', nargs='?', type=Path, help='CSV of poses to measure at')
    parser.add_argument('output', nargs='?', type=Path, help='measurement CSV to write')
    parser.add_argument('--check', type=Path, help='compare this payload file with the truth')
    arguments = parser.parse_args(argv)
    if arguments.check is None and (arguments.poses is None or arguments.output is None):
        parser.error('give POSES_CSV and MEASUREMENTS_CSV, or --check PAYLOAD_YAML')
    try:
        if arguments.check is not None:
            check(arguments.check)
        else:
            measure(arguments.poses, arguments.output)
    except (ValueError, OSError) as error:   # a file that cannot be read or written
        print(f'payload_example.py: error: {error}', file=sys.stderr)
        return 2
    return 0


if __name__ == '__main__':
    sys.exit(main())
