"""`cmake --install` puts an importable module under the prefix."""
import os
import subprocess
import sys

import pytest


def test_install_into_a_prefix(tmp_path):
    build = os.environ.get("AGGPACK_BUILD_DIR")
    if not build:
        pytest.fail("AGGPACK_BUILD_DIR is not set (ctest sets it)")
    result = subprocess.run(["cmake", "--install", build, "--prefix", str(tmp_path)],
                            capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    # Debian's layout for the prefix the build was configured with: /usr (after
    # scripts/package.sh) installs to lib/python3/dist-packages, any other prefix to
    # lib/python3.X/dist-packages; exactly one of them must hold the module.
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    candidates = [tmp_path / "lib" / name / "dist-packages" for name in (version, "python3")]
    holding = [c for c in candidates if c.is_dir() and any(c.glob("aggpack*.so"))]
    assert len(holding) == 1, f"module installed under {holding} (expected one of {candidates})"
    site = holding[0]
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    result = subprocess.run(
        [sys.executable, "-c", "import aggpack; print(aggpack.__file__); "
         "print(len(aggpack.pack(aggpack.pack_config(None, ['container.length=0.5']))))"],
        capture_output=True, text=True, env=env, cwd=str(tmp_path), check=False)
    assert result.returncode == 0, result.stderr
    where, count = result.stdout.split()
    assert where.startswith(str(site))
    assert int(count) > 0
