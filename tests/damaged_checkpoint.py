#!/usr/bin/python3
"""Damaged checkpoints (issue 49): a checkpoint is a file a user can damage, so --resume reads it
as untrusted input. Each damaged copy must be refused with exit code 1 and a message naming the
checkpoint, never end by a signal (a negative return code: the segfault of a cell id "zz", the
"stack smashing detected" of an over-long one) or hang; where the damage leaves a valid file (a
changed value, the checksum sealed again) the run may also end with 0.

Scene: the Hertz cylinder with two cycles of adaptive refinement on 1 rank (the checkpoint's
refinement history names cells by id), checkpoint at the end. Damages:
- truncated at many offsets (the manifest told the new size, or not);
- bytes flipped at many positions (the checksum then fails);
- crafted fields, the checksum sealed again: cell ids garbage, over-long, too deep, of another
  level, naming no cell or a refined one; huge counts of refinements, cells, characters,
  solution values and segments; another header, dimension or rank; non-finite or non-positive
  time and step size; bytes added before the end marker; an entry of the run's state renamed or
  longer than it reads;
- bytes flipped in the leading fields with the checksum sealed again (any exit but a signal);
- a damaged manifest, the rank file replaced by a directory, a damaged parameters.prm,
  statistics.csv shorter than the checkpoint says or cut inside a row.
Then the two-body patin with weighted conditions on 2 ranks, only rank 1's file damaged: every
rank stops with the message (none waits for the other).

The random offsets are drawn with SL_DAMAGE_SEED (printed)."""
import os
import random
import shutil
import signal
import struct
import subprocess
import sys
import sltest

executable, workdir = sys.argv[1], sys.argv[2]
check = sltest.Checker()
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sltest.seed_random("SL_DAMAGE_SEED", "damaged offsets")
MAGIC = b"stabilized_lagrangian checkpoint 6"
CRASH_SIGNS = ("Segmentation", "stack smashing", "core dumped", "terminate called", "Aborted",
               "double free", "corrupted", "std::bad_alloc")


def fnv1a(data):
    """The checksum of source/solver/checkpoint.cc (FNV-1a, 64 bits)."""
    h = 14695981039346656037
    for byte in data:
        h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def seal(body):
    """A rank file's bytes without their checksum -> with the checksum of the new bytes."""
    return body + struct.pack("<Q", fnv1a(body))


def layout(data):
    """Offsets of the leading fields of a rank file (write_checkpoint's order; the run's state
    by the names of its entries) and the cell ids: [(offset of the length, length)]."""
    fields, cells, pos = {}, [], 0

    def u64():
        nonlocal pos
        value = struct.unpack_from("<Q", data, pos)[0]
        pos += 8
        return value

    fields["header"] = pos
    length = u64()
    pos += length
    for name, size in (("dim", 4), ("n_ranks", 4), ("rank", 4), ("n_u", 8), ("n_multipliers", 8)):
        fields[name] = pos
        pos += size
    fields["n_refinements"] = pos
    for _ in range(u64()):
        fields.setdefault("n_cells", pos)
        for _ in range(u64()):
            cells.append((pos, struct.unpack_from("<Q", data, pos)[0]))
            pos += 8 + cells[-1][1]
    fields["cycle"] = pos
    pos += 4
    # the run's state (RunState::write): per entry its name, then its bytes
    fields["n_entries"] = pos
    entries = {}
    for _ in range(u64()):
        length = u64()
        name = data[pos:pos + length].decode()
        pos += length
        fields["size of " + name] = pos
        entries[name] = pos + 8
        pos += 8 + u64()
    fields["time"] = entries["time"]
    fields["step_size"] = entries["load stepping"] + 8  # LoadStepController::State: step, size
    fields["hold"] = entries["load stepping"] + 24  # ... cuts, steps at the size, hold
    fields["last_normal_force"] = entries["last normal force"]
    fields["n_solution"] = entries["solution"]
    fields["n_segments"] = entries["contact faces"]
    fields["n_states"] = entries["contact points"]
    return fields, cells


def scene(name, extra=""):
    return (sltest.read_prm(os.path.join(root, "prm", name)) + extra +
            "\nsubsection Output\n  set Output directory = output\n  set Checkpoint interval = 1\nend\n")


def command(ranks):
    c = [executable, "--resume", "input.prm"]
    return (["mpirun", "-np", str(ranks)] + c) if ranks > 1 else c


class Case:
    """A finished run's directory, its output kept as it was; each resume gets a fresh copy."""

    def __init__(self, name, text, ranks):
        self.directory, self.ranks = f"{workdir}/{name}", ranks
        shutil.rmtree(self.directory, ignore_errors=True)
        code, log = sltest.run(executable, text, self.directory, ranks=ranks, expect_success=False)
        check(code == 0, f"{name}: the run with checkpoints ends with 0")
        if code != 0:
            print(log[-2000:])
        self.pristine = f"{self.directory}/pristine"
        shutil.copytree(f"{self.directory}/output", self.pristine)
        self.checkpoint = f"{self.directory}/output/checkpoint"
        self.count = 0

    def rank_file(self, rank=0):
        with open(f"{self.pristine}/checkpoint/rank-{rank}.bin", "rb") as f:
            return f.read()

    def resume(self, what, files=None, manifest=True, change=None, refuse=True):
        """Resume from the pristine output with rank files `files` ({rank: bytes}; the manifest
        given their sizes if `manifest`) and `change(output directory)` applied. refuse: the run
        must end with 1 and a message naming the checkpoint; else it may also end with 0."""
        output = f"{self.directory}/output"
        shutil.rmtree(output)
        shutil.copytree(self.pristine, output)
        for rank, data in (files or {}).items():
            with open(f"{self.checkpoint}/rank-{rank}.bin", "wb") as f:
                f.write(data)
            if manifest:
                with open(f"{self.checkpoint}/manifest") as f:
                    lines = [line.split() for line in f]
                with open(f"{self.checkpoint}/manifest", "w") as f:
                    f.writelines(f"{key} {len(data) if key == f'rank-{rank}.bin' else value}\n"
                                 for key, value in lines)
        if change:
            change(output)
        self.count += 1
        # (a session of its own: a rank left waiting for another is killed with mpirun)
        process = subprocess.Popen(command(self.ranks), cwd=self.directory, env=sltest.MPI_ENV,
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                   errors="replace", start_new_session=True)
        try:
            log = process.communicate(timeout=60)[0]
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            check(False, f"{what}: still running after 60 s")
            return
        crashed = process.returncode < 0 or any(sign in log for sign in CRASH_SIGNS)
        lines = [line for line in log.splitlines() if line.startswith(("Input error", "Error"))]
        message = lines[0].strip() if lines else ""
        named = process.returncode == 1 and "checkpoint" in message
        good = not crashed and (named or (not refuse and process.returncode == 0))
        if refuse or not good:
            check(good, f"{what}: exit {process.returncode}: {message[:220]}")
        else:
            self.unchecked = getattr(self, "unchecked", 0) + 1
        if not good:
            print(log[-1500:])


# --- one rank: the adaptive Hertz cylinder -------------------------------------------------------
hertz = Case("hertz_adaptive",
             scene("hertz_cylinder.prm", sltest.nested_set("Adaptive refinement/Cycles", 2))
             .replace("set Global refinements      = 3", "set Global refinements      = 2")
             .replace("set Local refinements       = 4", "set Local refinements       = 1"), 1)
data = hertz.rank_file()
check(data[8:8 + len(MAGIC)] == MAGIC and struct.unpack("<Q", data[-8:])[0] == fnv1a(data[:-8]),
      f"the rank file is a version 5 checkpoint with its checksum ({len(data)} bytes)")
fields, cells = layout(data)
time_value = struct.unpack_from("<d", data, fields["time"])[0]
check(len(cells) > 0 and time_value == 1.0,
      f"the layout is read: {len(cells)} cell ids in the refinement history, t = {time_value}")
hertz.resume("the intact checkpoint", refuse=False)
check(getattr(hertz, "unchecked", 0) == 1, "the intact checkpoint resumes with exit 0")
body = data[:-8]


def put(offset, value, fmt="<Q"):
    """The body with the value at offset replaced, sealed again."""
    b = bytearray(body)
    struct.pack_into(fmt, b, offset, value)
    return seal(bytes(b))


def with_cell_id(text, index=0):
    """The body with cell id `index` replaced by `text` (bytes), sealed again."""
    offset, length = cells[index]
    return seal(body[:offset] + struct.pack("<Q", len(text)) + text + body[offset + 8 + length:])


def one_value_fewer(count, entry):
    """The body without the first value of the vector whose count is the field `count`, the size
    of its state `entry` told, sealed again."""
    offset, size = fields[count], fields["size of " + entry]
    n = struct.unpack_from("<Q", body, offset)[0]
    b = bytearray(body[:offset] + struct.pack("<Q", n - 1) + body[offset + 16:])
    struct.pack_into("<Q", b, size, struct.unpack_from("<Q", body, size)[0] - 8)
    return seal(bytes(b))


crafted = {
    "cell id 'zz'": with_cell_id(b"zz"),
    "an over-long cell id (level 40)": with_cell_id(b"0_40:" + b"0" * 40),
    "a cell id of 1000 characters": with_cell_id(b"7" * 1000),
    "a cell id of 5000 digits after its level": with_cell_id(b"2_3:" + b"0" * 5000),
    "a cell id shorter than its level": with_cell_id(b"2_3:01"),
    "a cell id with child index 9": with_cell_id(b"2_3:019"),
    "a cell id of a coarse cell the mesh lacks": with_cell_id(b"99999_1:0"),
    "a cell id of a refined cell": with_cell_id(b"0_0:"),
    "a cell id of level 25": with_cell_id(b"2_25:" + b"0" * 25),
    "an empty cell id": with_cell_id(b""),
    "a negative coarse cell": with_cell_id(b"-1_1:0"),
    "a coarse cell of 30 digits": with_cell_id(b"9" * 30 + b"_1:0"),
    "a cell id with a NUL byte": with_cell_id(b"2_3:0\x001"),
    "a cell id of non-ASCII bytes": with_cell_id(b"\xff\xfe_\x80:\x81"),
    "the last cell id garbage": with_cell_id(b"2_3:zzz", len(cells) - 1),
    "2^63 refinements": put(fields["n_refinements"], 2**63),
    "no refinements (the cycle says 2)": seal(body[:fields["n_refinements"]] + struct.pack("<Q", 0) +
                                              body[fields["cycle"]:]),
    "2^40 cells in a refinement": put(fields["n_cells"], 2**40),
    "a cell id of 2^64 - 1 characters": put(cells[0][0], 2**64 - 1),
    "2^61 solution values": put(fields["n_solution"], 2**61),
    "one solution value fewer": one_value_fewer("n_solution", "solution"),
    "2^62 segment values": put(fields["n_segments"], 2**62),
    "2^57 contact point states": put(fields["n_states"], 2**57),
    "a header of 2^62 characters": put(fields["header"], 2**62),
    "the header of another version": seal(body.replace(MAGIC, b"stabilized_lagrangian checkpoint 9", 1)),
    "a header of another program": seal(body.replace(MAGIC, b"xtabilized_lagrangian checkpoint 4", 1)),
    "dimension 3": put(fields["dim"], 3, "<i"),
    "rank 5": put(fields["rank"], 5, "<I"),
    "one more DoF": put(fields["n_u"], struct.unpack_from("<Q", body, fields["n_u"])[0] + 1),
    "time NaN": put(fields["time"], float("nan"), "<d"),
    "time -1": put(fields["time"], -1.0, "<d"),
    "step size 0": put(fields["step_size"], 0.0, "<d"),
    "step size -inf": put(fields["step_size"], float("-inf"), "<d"),
    "step hold 0": put(fields["hold"], 0, "<I"),
    "last normal force inf": put(fields["last_normal_force"], float("inf"), "<d"),
    "bytes added before the end marker": seal(body[:-len(MAGIC) - 8] + b"\0" * 8 + body[-len(MAGIC) - 8:]),
    "bytes added after the end marker": seal(body + b"\0" * 8),
    "bytes added to the state 'time'": seal(body[:fields["size of time"]] + struct.pack("<Q", 16) +
                                            body[fields["time"]:fields["time"] + 8] + b"\0" * 8 +
                                            body[fields["time"] + 8:]),
    "the state 'time' renamed": seal(body.replace(b"\x04\0\0\0\0\0\0\0time", b"\x04\0\0\0\0\0\0\0tame", 1)),
    "an empty file": b"",
    "zeros": b"\0" * len(data),
}
for what, damaged in crafted.items():
    hertz.resume(what, {0: damaged})

# truncated at many offsets (the manifest told the new size; a few without)
offsets = sorted({0, 1, 7, 8, 20, 42, 43, 50, fields["n_refinements"] + 3, cells[0][0] + 9,
                  len(data) // 2, len(data) - 9, len(data) - 8, len(data) - 1} |
                 {random.randrange(len(data)) for _ in range(6)})
for offset in offsets:
    hertz.resume(f"truncated at {offset} of {len(data)} bytes", {0: data[:offset]})
for offset in (0, len(data) // 3, len(data) - 1):
    hertz.resume(f"truncated at {offset}, the manifest not told", {0: data[:offset]}, manifest=False)

# bytes flipped at many positions: the checksum fails
positions = sorted({0, 8, fields["dim"], cells[0][0] + 8, len(data) - 9, len(data) - 1} |
                   {random.randrange(len(data)) for _ in range(8)})
for position in positions:
    b = bytearray(data)
    b[position] ^= 1 << random.randrange(8)
    hertz.resume(f"byte {position} flipped", {0: bytes(b)})

# bytes flipped in the fields before the solution (header, counts, cell ids, load stepping), the
# checksum sealed again: any exit but a signal
for _ in range(10):
    position = random.randrange(fields["n_solution"] + 8)
    b = bytearray(body)
    b[position] ^= 1 << random.randrange(8)
    hertz.resume(f"byte {position} flipped, sealed again", {0: seal(bytes(b))}, refuse=False)


def write(path, content, mode="w"):
    def change(output):
        target = os.path.join(output, path)
        if os.path.isdir(target):
            shutil.rmtree(target)
        elif os.path.exists(target):
            os.remove(target)
        if content is None:
            os.mkdir(target)
        else:
            with open(target, mode) as f:
                f.write(content)
    return change


def cut_row(output):
    """statistics.csv with its last newline (where the checkpoint says its rows end) replaced."""
    path = os.path.join(output, "statistics.csv")
    with open(path, "rb") as f:
        content = bytearray(f.read())
    content[-1:] = b"x"
    with open(path, "wb") as f:
        f.write(bytes(content))


manifest = open(f"{hertz.pristine}/checkpoint/manifest").read()
for what, change in (
        ("a manifest of garbage", write("checkpoint/manifest", "\x01\x02 garbage\n")),
        ("a manifest with the size 'abc'", write("checkpoint/manifest",
                                                manifest.replace(f"rank-0.bin {len(data)}", "rank-0.bin abc"))),
        ("a manifest with a 40-digit size", write("checkpoint/manifest",
                                                  manifest.replace(f"rank-0.bin {len(data)}", "rank-0.bin " + "9" * 40))),
        ("a manifest of 0 ranks", write("checkpoint/manifest", manifest.replace("ranks 1", "ranks 0"))),
        ("a manifest without its rank file", write("checkpoint/manifest",
                                                   manifest.replace(f"rank-0.bin {len(data)}", ""))),
        ("the rank file a directory", write("checkpoint/rank-0.bin", None)),
        ("parameters.prm of garbage", write("checkpoint/parameters.prm", os.urandom(2000), "wb")),
        ("statistics.csv shorter than the checkpoint says", write("statistics.csv", "step\n")),
        ("statistics.csv cut inside a row", cut_row)):
    hertz.resume(what, change=change)
print(f"{hertz.count} resumes of damaged copies of the 1-rank checkpoint, "
      f"{getattr(hertz, 'unchecked', 0) - 1} of them ended with 0")

# --- two ranks: only rank 1's file damaged; both stop ---------------------------------------------
two_bodies = Case("weighted_two_bodies_2_ranks",
                  scene("patin_deformable_block.prm",
                        sltest.nested_set("Contact/Complementarity", "weighted") +
                        sltest.nested_set("Output/Write vtu", "false"))
                  .replace("set Global refinements = 2", "set Global refinements = 1"), 2)
data = two_bodies.rank_file(1)
body = data[:-8]
fields, _ = layout(data)
b = bytearray(data)
b[len(data) // 2] ^= 0x10
for what, damaged in (("rank 1 truncated", data[:len(data) // 2]),
                      ("rank 1 with a byte flipped", bytes(b)),
                      ("rank 1 with 2^61 solution values", put(fields["n_solution"], 2**61)),
                      ("rank 1 with one solution value fewer", one_value_fewer("n_solution", "solution")),
                      ("rank 1 with 2^57 contact point states", put(fields["n_states"], 2**57))):
    two_bodies.resume(what, {1: damaged})
check.finish()
