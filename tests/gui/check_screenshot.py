#!/usr/bin/env python3
"""Checks an aggpack-gui screenshot: size, the dark control panel on the left, the light 3D view
on the right with many particle-coloured pixels, distinct particle colours, and the packed
particles centred in the view. Decodes the PNG itself (zlib + PNG filters) so it needs no
imaging library. Usage: check_screenshot.py FILE WIDTH HEIGHT"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG file"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, f"unsupported PNG {header}"
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up = previous[x]
            up_left = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
                line[x] = (line[x] + predictor) & 255
        rows.append(line)
        previous = line
    pixel = lambda x, y: tuple(rows[y][x * channels:x * channels + 3])
    return width, height, pixel


def main():
    path, want_width, want_height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    width, height, pixel = read_png(path)
    assert (width, height) == (want_width, want_height), f"size {width}x{height}"
    background = (236, 238, 242)  # RenderStyle::background
    panel = 360
    # Left: ImGui's dark panel.
    dark = sum(1 for y in range(0, height, 4) for x in range(0, panel - 10, 4)
               if sum(pixel(x, y)) < 200)
    total = len(range(0, height, 4)) * len(range(0, panel - 10, 4))
    assert dark > 0.5 * total, f"panel not dark: {dark} of {total}"
    # Right: the 3D view, background plus particles.
    colours, covered, samples, xs, ys = set(), 0, 0, [], []
    for y in range(0, height, 3):
        for x in range(panel + 2, width, 3):
            samples += 1
            c = pixel(x, y)
            if c == background:
                continue
            if max(c) - min(c) < 12:  # grey: container outline, anti-aliasing
                continue
            covered += 1
            colours.add((c[0] // 24, c[1] // 24, c[2] // 24))
            xs.append(x)
            ys.append(y)
    assert covered > 0.05 * samples, f"too few particle pixels: {covered} of {samples}"
    assert covered < 0.9 * samples, f"view has no background: {covered} of {samples}"
    assert len(colours) > 20, f"particles not distinctly coloured: {len(colours)} colours"
    cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
    view_cx, view_cy = (panel + width) / 2, height / 2
    assert abs(cx - view_cx) < 0.15 * (width - panel), f"particles off centre: x {cx:.0f}"
    assert abs(cy - view_cy) < 0.15 * height, f"particles off centre: y {cy:.0f}"
    print(f"screenshot ok: {width}x{height}, {covered}/{samples} particle samples, "
          f"{len(colours)} colours, centre ({cx:.0f}, {cy:.0f})")


if __name__ == "__main__":
    main()
