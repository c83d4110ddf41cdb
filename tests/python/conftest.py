import os
import shutil

import pytest


@pytest.fixture
def cli():
    """The archipelago-cli binary (ctest passes its path in ARCHIPELAGO_CLI)."""
    path = os.environ.get("ARCHIPELAGO_CLI") or shutil.which("archipelago-cli")
    if not path:
        pytest.skip("archipelago-cli not found")
    return path
