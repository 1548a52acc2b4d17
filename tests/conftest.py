import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CONFIGS = ROOT / "configs"

os.environ.setdefault("MPLBACKEND", "Agg")


def run_cli(*args, cwd=None):
    """Run ``python -m mechcli ARGS`` in a subprocess; return CompletedProcess."""
    return subprocess.run([sys.executable, "-m", "mechcli", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd or ROOT, timeout=300)


@pytest.fixture
def cli():
    return run_cli
