"""Malformed LIGGGHTS/LAMMPS dumps (issue #25): a clear DumpError naming the file and the line,
never a traceback from deep inside numpy, a hang or a read of the whole file into memory."""
import time

import numpy as np
import pytest

from xclib import dumps as D

GOOD = (b"ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
        b"ITEM: ATOMS id x vx\n1 0.5 0.0\n2 0.25 1.5\n")


def frames_of(tmp_path, text):
    p = tmp_path / "dump.atoms"
    p.write_bytes(text)
    return list(D.frames(str(p)))


def test_good_dump_reads(tmp_path):
    (step, cols, rows), = frames_of(tmp_path, GOOD)
    assert step == 100 and cols == ["id", "x", "vx"] and np.array_equal(rows[:, 2], [0.0, 1.5])


@pytest.mark.parametrize("name, text, words", [
    ("cut short in the header", GOOD[:30], "ends at line"),
    ("cut short in the rows", GOOD[:-10], "values, expected 2 x 3"),
    ("a step that is no number", GOOD.replace(b"\n100\n", b"\n1x0\n"), "expected the time step"),
    ("a row count that is no number", GOOD.replace(b"ATOMS\n2\n", b"ATOMS\ntwo\n"), "number of rows"),
    ("a negative row count", GOOD.replace(b"ATOMS\n2\n", b"ATOMS\n-5\n"), "claims -5 rows"),
    ("a row count past the file", GOOD.replace(b"ATOMS\n2\n", b"ATOMS\n999999999999\n"), "more than the rest"),
    ("a value that is no number", GOOD.replace(b"0.25", b"0.2x"), "values, expected"),
    ("bytes that are no text", GOOD.replace(b"0.25", b"\xff\xfe"), "values"),
    ("no ATOMS line", GOOD.replace(b"ITEM: ATOMS id x vx", b"ITEM: ATOMZ"), "ends at line"),
])
def test_malformed_dump_is_a_dump_error(tmp_path, name, text, words):
    p = tmp_path / "dump.atoms"
    t = time.time()
    with pytest.raises(D.DumpError) as e:
        frames_of(tmp_path, text)
    assert str(p) in str(e.value) and words in str(e.value), name
    assert time.time() - t < 5


def test_lockstep_names_a_missing_step(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.write_bytes(GOOD + GOOD.replace(b"\n100\n", b"\n200\n"))
    b.write_bytes(GOOD.replace(b"ITEM: ATOMS", b"ITEM: ENTRIES"))
    with pytest.raises(D.DumpError, match="ends before step 200"):
        list(D.lockstep(str(a), str(b)))
