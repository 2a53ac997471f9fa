"""Shared fixtures: the tests' folder on the import path, a local Ray for the Ray tests."""

import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))


@pytest.fixture(scope="module")
def ray_two_workers():
    """A local Ray on 127.0.0.1 with two CPUs, for a module's Ray tests (its workers find the
    tests' job functions through PYTHONPATH, as they find the project's); stopped after it."""
    import ray

    here = str(Path(__file__).resolve().parent)
    before = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (here, before) if p)
    try:
        ray.init(num_cpus=2, _node_ip_address="127.0.0.1", include_dashboard=False,
                 log_to_driver=False)
    finally:
        if before is None:
            del os.environ["PYTHONPATH"]
        else:
            os.environ["PYTHONPATH"] = before
    yield ray
    ray.shutdown()
