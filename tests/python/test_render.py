"""Headless rendering to a numpy image and a PNG."""
import numpy as np
import pytest

import aggpack


@pytest.mark.skipif(not aggpack.has_render, reason="built without rendering")
def test_render_image_and_png(small_packing, tmp_path):
    image = small_packing.render(str(tmp_path / "run.png"), width=200, height=120)
    assert image.shape == (120, 200, 4) and image.dtype == np.uint8
    rgb = image[:, :, :3].reshape(-1, 3)
    # Not blank: the background and many other colours (the particles' hues, shading).
    assert len(np.unique(rgb, axis=0)) > 50
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The centre of the iso view holds particles, unlike the corner (background).
    assert not np.array_equal(image[60, 100], image[0, 0])
    # A second render to the same path is refused, as `aggpack render` without -f; force=True
    # replaces the file.
    (tmp_path / "run.png").write_bytes(b"keep me")
    with pytest.raises(aggpack.IoError, match="force=True"):
        small_packing.render(str(tmp_path / "run.png"), width=200, height=120)
    assert (tmp_path / "run.png").read_bytes() == b"keep me"
    small_packing.render(str(tmp_path / "run.png"), width=200, height=120, force=True)
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.skipif(not aggpack.has_render, reason="built without rendering")
def test_render_bad_keyword(small_packing):
    with pytest.raises(aggpack.InvalidInput, match="view"):
        small_packing.render(view="diagonal")
