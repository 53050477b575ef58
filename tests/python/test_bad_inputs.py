"""aggpack.read refuses every bad native file of tests/io/fixtures/bad-inputs (README there) with
the CLI's one-line message: the same validation (read_packing) as every command."""
import os
import pathlib

import pytest

import aggpack

FIXTURES = pathlib.Path(os.environ.get("AGGPACK_SOURCE_DIR", ".")) / "tests/io/fixtures/bad-inputs"
# The fixtures that are valid packings (read; tests/io/native_bad_inputs_test.cpp checks them).
VALID = {"base_s.h5", "vlen_ascii.h5", "vlen_format_name.h5", "vlen_utf8_config_toml.h5",
         "zero_particles.h5", "unparsable_config_toml.h5"}
BAD = sorted(p.name for p in FIXTURES.glob("*.h5") if p.name not in VALID)


def test_the_fixtures_are_there():
    # An empty list would make the test below pass without checking anything.
    assert "wall_gap_over_half.h5" in BAD and "format_name_embedded_nul.h5" in BAD
    assert len(BAD) == 18


@pytest.mark.parametrize("name", BAD)
def test_read_refuses_like_the_cli(name, cli):
    path = str(FIXTURES / name)
    with pytest.raises(aggpack.FormatError) as caught:
        aggpack.read(path)
    message = str(caught.value)
    assert message.startswith(path + ": /"), message
    assert "\n" not in message
    result = cli("info", path)
    assert result.returncode == 2
    assert result.stderr == "aggpack: error: " + message + "\n"
