#!/usr/bin/env python3
"""Writes the .prm files of this folder (run from it; they are kept in git, never regenerated silently).

claims_2m_triangles.prm  1,000 bytes with a valid header and CRC whose connectivity section claims one component of
                         2,640,962 triangles (the most spec §4.3 lets 920 bytes of CLERS data claim) over zero
                         bytes: it fails at the second symbol (bad_connectivity, §6.4). Before spec §4.5 decoding
                         it allocated 71 MB; `prm info` exited 0 on it.
bad_crc.prm              the tetrahedron of spec §3.6 (what `prm encode common/tests/data/tet.off` writes), its
                         last CRC byte flipped (crc_mismatch, §3.5).
"""
import struct
import zlib


def varint(v):
    out = b""
    while True:
        b, v = v & 0x7F, v >> 7
        out += bytes([b | 0x80 if v else b])
        if not v:
            return out


def with_crc(body):
    return body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF)


def claims_most_triangles(total):
    length = total - 80
    triangles = 2880 * (length - 3) + 2
    header = b"PRM\x1a" + bytes([1, 4, 0, 12]) + varint(triangles // 2 + 2) + varint(triangles)
    header += struct.pack("<4d", 0, 0, 0, 1.0) + varint(0) * 3 + varint(4095) * 3
    conn = varint(1) + varint(triangles) + varint(0) + varint(0) + bytes(length)
    body = header + bytes([1]) + varint(len(conn)) + conn + bytes([2, 4]) + bytes(4)
    return with_crc(body)


# The tetrahedron of spec §3.6 (100 bytes).
TET = bytes.fromhex(
    "50524d1a0100000c040400000000000000000000000000000000000000000000"
    "0000100001100001303f000000ff1fff1fff1f0108010400007fff8000022100"
    "0ffdfc5450cb9a97ffffd832d9d2db10c75aab16aad58dde266d9e533cf13200"
    "d8d8e8ba")

if __name__ == "__main__":
    open("claims_2m_triangles.prm", "wb").write(claims_most_triangles(1000))
    open("bad_crc.prm", "wb").write(TET[:-1] + bytes([TET[-1] ^ 0x01]))
