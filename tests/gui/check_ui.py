#!/usr/bin/env python3
"""Checks what an aggpack-gui screenshot shows, by pixel content (check_screenshot.read_png):
  default   the window at start: the menu bar on top and the status bar at the bottom (dark,
            full width), the dark panel on the left, the light 3D view with the empty
            container's outline and the axes triad (red, green and blue strokes)
  stale     the Export dialog asking about an out-of-date result: a dark modal over the view
            with the warning's amber text
  error     a field's error in the panel: red text in the panel's area
  deck      the Export dialog with a solver deck's fields, one out of range: a dark modal with
            the bad field's red frame and the red error text under the fields
  cjk       the window in Chinese (FILE) against the same run in English (ENGLISH): the status
            bar's first line of text is drawn with CJK glyphs, whose strokes fill their columns
            far more than Latin letters do (a missing glyph is a sparse '?')
Usage: check_ui.py WHAT FILE WIDTH HEIGHT [ENGLISH]"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_screenshot import read_png  # noqa: E402

PANEL = 360
BACKGROUND = (236, 238, 242)


def count(pixel, xs, ys, test):
    return sum(1 for y in ys for x in xs if test(pixel(x, y)))


def is_dark(c):
    return sum(c) < 200


def first_line_ink(path):
    """The status bar's first line of text: (inked columns, mean ink per inked column, columns
    with 6 or more inked pixels)."""
    width, height, pixel = read_png(path)
    y = height - 1
    while sum(pixel(700, y)) < 200:  # up to the view's light background
        y -= 1
    top = y + 1

    def ink(c):
        return sum(c) > 240
    rows = [sum(1 for x in range(0, 560) if ink(pixel(x, y))) for y in range(top, height)]
    k = 0
    while k < len(rows) and rows[k] == 0:
        k += 1
    start = k
    while k < len(rows) and rows[k] > 0:
        k += 1
    line = range(top + start, top + k)
    columns = [sum(1 for y in line if ink(pixel(x, y))) for x in range(0, 560)]
    inked = [c for c in columns if c > 0]
    assert len(inked) > 100, f"{path}: no status text ({len(inked)} inked columns)"
    return len(inked), sum(inked) / len(inked), sum(1 for c in inked if c >= 6)


def main():
    what, path, want_width, want_height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    width, height, pixel = read_png(path)
    assert (width, height) == (want_width, want_height), f"size {width}x{height}"
    view_xs = range(PANEL + 10, width - 10, 4)
    if what == "default":
        # Menu bar: the top rows are dark right across the view too.
        top = count(pixel, view_xs, [4, 10], is_dark)
        assert top > 0.9 * 2 * len(view_xs), f"no menu bar across the top: {top}"
        # Status bar: the bottom rows are dark across the view's width.
        bottom = count(pixel, view_xs, [height - 8, height - 20], is_dark)
        assert bottom > 0.9 * 2 * len(view_xs), f"no status bar at the bottom: {bottom}"
        # The view between them: mostly the light background (no packing yet).
        ys = range(60, height - 90, 4)
        light = count(pixel, view_xs, ys, lambda c: c == BACKGROUND)
        assert light > 0.6 * len(view_xs) * len(ys), f"view not mostly background: {light}"
        # Panel: dark.
        dark = count(pixel, range(0, PANEL - 10, 4), ys, is_dark)
        assert dark > 0.5 * len(range(0, PANEL - 10, 4)) * len(ys), f"panel not dark: {dark}"
        # Axes triad, lower left of the view: red, green and blue strokes.
        xs, ys = range(PANEL, PANEL + 100), range(height - 160, height - 50)
        for name, test in (("x red", lambda c: c[0] > 150 and c[1] < 90 and c[2] < 90),
                           ("y green", lambda c: c[1] > 110 and c[0] < 90 and c[2] < 90),
                           ("z blue", lambda c: c[2] > 150 and c[0] < 90 and c[1] < 120)):
            found = count(pixel, xs, ys, test)
            assert found > 10, f"axes triad: no {name} stroke ({found} pixels)"
    elif what == "cjk":
        zh_columns, zh_density, zh_full = first_line_ink(path)
        en_columns, en_density, en_full = first_line_ink(sys.argv[5])
        print(f"status line: Chinese {zh_columns} columns, {zh_density:.2f} ink/column, "
              f"{zh_full} full; English {en_columns}, {en_density:.2f}, {en_full}")
        assert zh_density > 1.45 * en_density, "the Chinese status line is not denser (CJK glyphs?)"
        assert zh_full > 2 * en_full, "too few dense columns: CJK glyphs not drawn"
    elif what == "stale":
        # The modal dialog in the middle of the window: dark, with amber warning text.
        xs = range(width // 2 - 280, width // 2 + 280, 2)
        ys = range(height // 2 - 200, height // 2 + 200, 2)
        dark = count(pixel, xs, ys, is_dark)
        assert dark > 0.4 * len(xs) * len(ys), f"no dialog in the middle: {dark}"
        amber = count(pixel, range(width // 2 - 300, width // 2 + 300),
                      range(height // 2 - 220, height // 2 + 220),
                      lambda c: c[0] > 200 and 150 < c[1] < 215 and c[2] < 120)
        assert amber > 40, f"no amber warning text in the dialog: {amber} pixels"
    elif what == "error":
        red = count(pixel, range(0, PANEL), range(0, height),
                    lambda c: c[0] > 200 and c[1] < 120 and c[2] < 110)
        assert red > 60, f"no red error text in the panel: {red} pixels"
    elif what == "deck":
        xs = range(width // 2 - 300, width // 2 + 300)
        ys = range(height // 2 - 280, height // 2 + 280)
        dark = count(pixel, xs[::2], ys[::2], is_dark)
        assert dark > 0.3 * len(xs[::2]) * len(ys[::2]), f"no dialog in the middle: {dark}"
        # The marked field's frame (config_panel's kErrorFrame, 0.55 0.15 0.12): a filled box.
        frame = count(pixel, xs, ys, lambda c: 120 < c[0] < 160 and 25 < c[1] < 55 and c[2] < 50)
        assert frame > 1500, f"no red field frame in the dialog: {frame} pixels"
        red = count(pixel, xs, ys, lambda c: c[0] > 200 and c[1] < 120 and c[2] < 110)
        assert red > 60, f"no red error text in the dialog: {red} pixels"
    elif what == "library":
        # The shape library dialog in the middle, its picked files' rows highlighted (ImGui's
        # header colour: blue over the dark dialog).
        xs = range(width // 2 - 280, width // 2 + 280, 2)
        ys = range(height // 2 - 200, height // 2 + 200, 2)
        dark = count(pixel, xs, ys, is_dark)
        assert dark > 0.4 * len(xs) * len(ys), f"no dialog in the middle: {dark}"
        picked = count(pixel, xs, ys, lambda c: c[2] > 90 and c[2] > c[0] + 40 and c[1] > c[0])
        assert picked > 500, f"no highlighted (picked) rows in the dialog: {picked} pixels"
    else:
        raise SystemExit(f"unknown check {what}")
    print(f"check_ui {what}: ok")


if __name__ == "__main__":
    main()
