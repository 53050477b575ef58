"""Library errors arrive as aggpack exceptions with the CLI's one-line messages."""
import pytest

import aggpack


def test_hierarchy_mirrors_the_library():
    assert issubclass(aggpack.InvalidInput, aggpack.Error)
    assert issubclass(aggpack.InvalidInput, ValueError)
    assert issubclass(aggpack.ConfigError, aggpack.InvalidInput)
    assert issubclass(aggpack.IoError, aggpack.Error) and issubclass(aggpack.IoError, OSError)
    assert issubclass(aggpack.FormatError, aggpack.Error)
    assert issubclass(aggpack.LimitExceeded, aggpack.Error)


def test_bad_value_in_a_dict_names_the_key():
    with pytest.raises(aggpack.ConfigError) as caught:
        aggpack.pack_config({"packer": {"kind": "random", "gap": -1.0}})
    assert caught.value.key == "packer.gap"
    assert caught.value.field == "packer.gap"
    assert caught.value.kind == "invalid input"
    message = str(caught.value)
    assert "packer.gap" in message and "-1" in message and "\n" not in message


def test_unknown_key_names_it():
    with pytest.raises(aggpack.ConfigError, match="packer.gapp"):
        aggpack.pack_config("[packer]\ngapp = 0.001\n")


def test_toml_syntax_error_is_a_format_error():
    with pytest.raises(aggpack.FormatError, match="config"):
        aggpack.pack_config("[packer\n")


def test_same_message_as_the_cli(tmp_path, cli):
    bad = tmp_path / "bad.toml"
    bad.write_text('[container]\nlength = -2.0\n')
    result = cli("pack", str(bad), "-o", str(tmp_path / "x.h5"))
    assert result.returncode != 0
    with pytest.raises(aggpack.ConfigError) as caught:
        aggpack.PackConfig.from_file(str(bad))
    assert caught.value.key == "container.length"
    assert result.stderr.strip() == "aggpack: error: " + str(caught.value)
    # --set overrides give the CLI's --set message too.
    result = cli("pack", "--set", "packer.seed=-5", "-o", str(tmp_path / "y.h5"))
    with pytest.raises(aggpack.ConfigError) as caught:
        aggpack.pack_config(None, ["packer.seed=-5"])
    assert result.stderr.strip() == "aggpack: error: " + str(caught.value)
    assert not (tmp_path / "x.h5").exists() and not (tmp_path / "y.h5").exists()


def test_generator_keyword_out_of_range():
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.generate_particle(alpha=1.5)
    assert caught.value.field == "alpha" and "alpha = 1.5" in str(caught.value)
    with pytest.raises(aggpack.LimitExceeded, match="edge_length"):
        aggpack.generate_particle(radius=1.0, edge_length=1e-4)


def test_missing_and_corrupt_files(tmp_path):
    with pytest.raises(aggpack.IoError, match="missing.h5"):
        aggpack.read(str(tmp_path / "missing.h5"))
    junk = tmp_path / "junk.h5"
    junk.write_bytes(b"not an hdf5 file at all" * 10)
    with pytest.raises(aggpack.FormatError, match="junk.h5"):
        aggpack.read(str(junk))


def test_bad_export_keyword_and_word(small_packing, tmp_path):
    with pytest.raises(aggpack.InvalidInput, match="cells = 'volume'"):
        small_packing.export(str(tmp_path / "a.vtu"), cells="volume")
    with pytest.raises(aggpack.InvalidInput, match="'colour'"):
        small_packing.export(str(tmp_path / "a.vtu"), colour="red")
    with pytest.raises(aggpack.InvalidInput, match="extension"):
        small_packing.export(str(tmp_path / "a.unknown"))
    assert list(tmp_path.iterdir()) == []


def test_an_existing_file_is_refused_unless_forced(small_packing, tmp_path):
    # As the CLI: an existing output is kept (IoError naming it) unless force=True replaces it.
    for name, write in [("run.h5", lambda p, **k: small_packing.write(p, **k)),
                        ("run.vtu", lambda p, **k: small_packing.export(p, **k)),
                        ("run.stl", lambda p, **k: small_packing.export(p, format="stl", **k))]:
        path = tmp_path / name
        path.write_text("keep me")
        with pytest.raises(aggpack.IoError, match=r"exists \(pass force=True"):
            write(str(path))
        assert path.read_text() == "keep me"
        write(str(path), force=True)
        assert path.read_bytes() != b"keep me"
        assert path.stat().st_size > 100
