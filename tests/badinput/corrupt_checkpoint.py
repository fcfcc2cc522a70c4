"""Damages a sweep checkpoint in one of the ways a disk, a copy or a hand can: used by
checkpoint_corruption_test.sh. usage: corrupt_checkpoint.py FILE SWEEP MODE [SEED]
  flip-done-cell    one byte of a done cell's first response, in the stored chunk
  status-7777       the status of a done cell rewritten through HDF5 (checksum stays valid)
  done-uncomputed   done flags set through HDF5 on cells that were never computed
  random-blocks     three 16-byte blocks of random bytes at random offsets (seeded)
  flip-status-chunk one byte in the middle of the first stored chunk of status (any file)
Prints the cell or offsets it touched."""
import random
import sys

import h5py
import numpy as np

path, sweep, mode = sys.argv[1], sys.argv[2], sys.argv[3]
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1


def first_done(group):
    done = group["done"][()].reshape(-1)
    cells = np.flatnonzero(done)
    if cells.size == 0:
        sys.exit("corrupt_checkpoint: no done cell in " + path)
    return int(cells[0])


if mode == "flip-done-cell":
    with h5py.File(path, "r") as f:
        g = f["sweeps/" + sweep]
        name = g.attrs["response_order"][0]
        name = name.decode() if isinstance(name, bytes) else name
        ds = g["responses/" + name]
        cell = first_done(g)
        coord = np.unravel_index(cell, ds.shape)
        chunk = ds.chunks
        origin = tuple(c // k * k for c, k in zip(coord, chunk))
        info = ds.id.get_chunk_info_by_coord(origin)
        # Uncompressed chunk: elements in row-major order within the chunk, then the checksum.
        inner = np.ravel_multi_index(tuple(c - o for c, o in zip(coord, origin)), chunk)
        offset = info.byte_offset + inner * ds.dtype.itemsize + 3
    with open(path, "r+b") as raw:
        raw.seek(offset)
        byte = raw.read(1)[0]
        raw.seek(offset)
        raw.write(bytes([byte ^ 0x10]))
    print(f"flipped byte {offset} of responses/{name} cell {cell}")
elif mode == "status-7777":
    with h5py.File(path, "r+") as f:
        g = f["sweeps/" + sweep]
        cell = first_done(g)
        status = g["status"]
        flat = status[()].reshape(-1)
        flat[cell] = 7777
        status[...] = flat.reshape(status.shape)
    print(f"status of cell {cell} set to 7777")
elif mode == "done-uncomputed":
    with h5py.File(path, "r+") as f:
        g = f["sweeps/" + sweep]
        done = g["done"][()].reshape(-1)
        todo = np.flatnonzero(done == 0)
        if todo.size == 0:
            sys.exit("corrupt_checkpoint: every cell is done in " + path)
        done[todo[: min(100, todo.size)]] = 1
        g["done"][...] = done.reshape(g["done"].shape)
    print(f"done flags set on {min(100, todo.size)} uncomputed cells")
elif mode == "random-blocks":
    rng = random.Random(seed)
    with open(path, "r+b") as raw:
        size = raw.seek(0, 2)
        for _ in range(3):
            offset = rng.randrange(0, size - 16)
            raw.seek(offset)
            raw.write(bytes(rng.randrange(256) for _ in range(16)))
            print(f"wrote 16 random bytes at {offset} of {size}")
elif mode == "flip-status-chunk":
    with h5py.File(path, "r") as f:
        ds = f["sweeps/" + sweep + "/status"]
        info = ds.id.get_chunk_info(0)
        offset = info.byte_offset + info.size // 2
    with open(path, "r+b") as raw:
        raw.seek(offset)
        byte = raw.read(1)[0]
        raw.seek(offset)
        raw.write(bytes([byte ^ 0x01]))
    print(f"flipped byte {offset} of status")
else:
    sys.exit("corrupt_checkpoint: unknown mode " + mode)
