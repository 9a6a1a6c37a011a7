"""A minimal reader of 16-bit greyscale PNGs (what `depthtrack synth` writes), stdlib zlib + numpy:
the tests read the synthesized frames without the bindings' own image code."""
import struct
import zlib

import numpy as np


def _unfilter(kind, row, prior, bpp):
    out = bytearray(row)
    if kind == 0:
        return out
    if kind == 2:
        return bytearray((np.frombuffer(row, np.uint8) + np.frombuffer(prior, np.uint8)).astype(np.uint8).tobytes())
    for i in range(len(out)):
        a = out[i - bpp] if i >= bpp else 0
        b = prior[i]
        c = prior[i - bpp] if i >= bpp else 0
        if kind == 1:
            predictor = a
        elif kind == 3:
            predictor = (a + b) // 2
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
        else:
            raise ValueError(f"PNG filter type {kind}")
        out[i] = (out[i] + predictor) & 0xFF
    return out


def read_png16(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos : pos + 8])
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (16, 0, 0), (path, depth, colour, interlace)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = 2 * width
    rows, prior = [], bytearray(stride)
    for v in range(height):
        start = v * (stride + 1)
        prior = _unfilter(raw[start], raw[start + 1 : start + 1 + stride], prior, 2)
        rows.append(bytes(prior))
    return np.frombuffer(b"".join(rows), ">u2").reshape(height, width).astype(np.uint16)
