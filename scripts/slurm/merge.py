#!/usr/bin/python3
"""Joins the pieces of a sample_array.sbatch array job into one .npz.

    scripts/slurm/merge.py OUT_DIR MERGED.npz [--tasks N]

OUT_DIR holds task_<T>.npz and task_<T>.json of tasks 0 .. N-1 (N: --tasks, else the array's
size as the tasks recorded it). Every piece must be there and complete: a readable .npz with
the members of the others, the scenes T*K .. (T+1)*K-1, the seed, configuration (its SHA-256)
and flags of the run. Then MERGED.npz gets every per-scene array concatenated in task order and
the others (names, seed) once: equal, array for array, to one process's --scenes N*K. Arrays
are streamed, so memory stays bounded for any size.

Otherwise nothing is written: each missing, failed or bad task is named with the reason, and
the one command that re-runs only those is printed (exit status 1). Exit status 2: usage, or
OUT_DIR holds tasks of different runs.
"""

import argparse
import json
import os
import re
import shlex
import sys
import tempfile
import zipfile

import numpy as np

# The sample_scenes .npz members: the per-scene ones (first axis = scene) and the per-file ones.
PER_SCENE = {"position", "orientation", "attempts", "success", "scene", "stable", "moved",
             "turned", "fallen", "sampled_position", "sampled_orientation", "rest_pose"}
PER_FILE = {"names", "seed"}
# The fields of task_<T>.json that must be equal in every task of one run.
RUN_FIELDS = ("config", "config_sha256", "seed", "scenes", "flags")
CHUNK = 8 << 20  # bytes copied at a time
STAMP = (1980, 1, 1, 0, 0, 0)  # as sample_scenes: the same pieces give the same file bytes

TASK_FILE = re.compile(r"^task_(\d+)\.(npz|json)$")


class BadPiece(Exception):
    """A piece that cannot be merged; the message says why."""


class BadTask(Exception):
    """A piece found bad while it was copied (a CRC error): its task and why."""

    def __init__(self, task, why):
        super().__init__(why)
        self.task = task


class UnknownArray(Exception):
    """A member this script does not know how to join (a newer sample_scenes?)."""


def npy_header(stream):
    """Reads a .npy header: (shape, dtype)."""
    version = np.lib.format.read_magic(stream)
    if version == (1, 0):
        shape, fortran, dtype = np.lib.format.read_array_header_1_0(stream)
    elif version == (2, 0):
        shape, fortran, dtype = np.lib.format.read_array_header_2_0(stream)
    else:
        raise BadPiece("unknown .npy version %s" % (version,))
    if fortran:
        raise BadPiece("a Fortran-ordered array")
    return shape, dtype


class Piece:
    """One task's .npz: its members' shapes and types, checked against the run."""

    def __init__(self, path, first, scenes, seed):
        self.path = path
        self.members = {}  # name -> (shape, dtype, offset of the data in the member)
        try:
            with zipfile.ZipFile(path) as z:
                for info in z.infolist():
                    if not info.filename.endswith(".npy"):
                        raise BadPiece("member %r is not a .npy array" % info.filename)
                    name = info.filename[:-4]
                    with z.open(info) as f:
                        shape, dtype = npy_header(f)
                        offset = f.tell()
                    size = int(np.prod(shape, dtype=np.uint64)) * dtype.itemsize
                    if info.file_size != offset + size:
                        raise BadPiece("%s: %d bytes, its header %s %s needs %d" % (
                            name, info.file_size, dtype.str, shape, offset + size))
                    self.members[name] = (shape, dtype, offset)
                for name in ("names", "seed", "scene"):
                    if name not in self.members:
                        raise BadPiece("no %r array" % name)
                for name, (shape, _, _) in self.members.items():
                    if name not in PER_SCENE and name not in PER_FILE and len(shape) != 0:
                        raise UnknownArray(
                            "array %r (shape %s) is neither a known per-scene array nor a scalar: "
                            "this merge.py does not know how to join it" % (name, shape))
                # names, seed and any other scalar (a digest): equal in every piece.
                self.constants = {n: self.read(z, n) for n in self.members if n not in PER_SCENE}
                scene = self.read(z, "scene")
        except (OSError, zipfile.BadZipFile, ValueError, EOFError) as e:
            raise BadPiece("not a complete .npz (%s)" % e)
        for name, (shape, _, _) in self.members.items():
            if name in PER_SCENE and (len(shape) == 0 or shape[0] != scenes):
                raise BadPiece("%s has shape %s, expected %d scenes" % (name, shape, scenes))
        if int(self.constants["seed"]) != seed:
            raise BadPiece("seed %d, expected %d" % (int(self.constants["seed"]), seed))
        expected = np.arange(first, first + scenes, dtype=np.uint64)
        if not np.array_equal(scene, expected):
            bad = int(np.argmax(scene != expected))
            raise BadPiece("scene %d at row %d, expected scenes %d .. %d" % (
                int(scene[bad]), bad, first, first + scenes - 1))

    @staticmethod
    def read(z, name):
        with z.open(name + ".npy") as f:
            return np.lib.format.read_array(f, allow_pickle=False)

    def layout(self):
        """What must be equal between pieces: members, types, shapes past the scene axis."""
        return {n: (dtype.str, shape[1:] if n in PER_SCENE else shape)
                for n, (shape, dtype, _) in self.members.items()}


def task_ranges(tasks):
    """[0, 1, 2, 5] -> '0-2,5' (sbatch --array's syntax)."""
    parts, i = [], 0
    while i < len(tasks):
        j = i
        while j + 1 < len(tasks) and tasks[j + 1] == tasks[j] + 1:
            j += 1
        parts.append(str(tasks[i]) if i == j else "%d-%d" % (tasks[i], tasks[j]))
        i = j + 1
    return ",".join(parts)


def load_records(out_dir):
    """task -> its task_<T>.json (None when unreadable), and the tasks with a .npz."""
    records, pieces = {}, set()
    for entry in os.listdir(out_dir):
        m = TASK_FILE.match(entry)
        if not m:
            continue
        task = int(m.group(1))
        if m.group(2) == "npz":
            pieces.add(task)
            continue
        try:
            with open(os.path.join(out_dir, entry)) as f:
                records[task] = json.load(f)
        except (OSError, ValueError):
            records[task] = None
    return records, pieces


def run_of(record):
    return tuple(json.dumps(record.get(k), sort_keys=True) for k in RUN_FIELDS)


def problem_of(task, record, out_dir, has_piece):
    """Why a task's piece is not there (None when its record says done)."""
    name = "task_%06d" % task
    if record is None:
        if has_piece:
            return "%s.json is missing or unreadable: the piece cannot be checked" % name
        return "missing: nothing of it in OUT_DIR (it never started)"
    state = record.get("state")
    where = "on %s at %s" % (record.get("host"), record.get("time"))
    last = record.get("last_message") or "no message"
    if state == "running":
        return ("started %s and did not finish (still running, or killed before it could say "
                "so: see %s.log)" % (where, name))
    if state == "killed":
        return "stopped by a signal (scancel or the time limit) %s" % where
    if state == "failed":
        return "failed %s: sample_scenes exited with status %s: %s" % (
            where, record.get("status"), last)
    if state != "done":
        return "%s.json has an unknown state %r" % (name, state)
    if not has_piece:
        return "done %s, but %s.npz is not in OUT_DIR" % (where, name)
    return None


def copy_member(src, name, skip, dst, size):
    """Copies member name's data (past skip header bytes) of zip src into stream dst."""
    with src.open(name + ".npy") as f:
        f.read(skip)
        left = size
        while left > 0:
            block = f.read(min(CHUNK, left))
            if not block:
                raise BadPiece("%s ends early" % name)
            dst.write(block)
            left -= len(block)
        if f.read(1):
            raise BadPiece("%s is longer than its header says" % name)


def member(out, name):
    """A stored member of out, written as a stream."""
    info = zipfile.ZipInfo(name + ".npy", date_time=STAMP)
    info.compress_type = zipfile.ZIP_STORED
    return out.open(info, "w", force_zip64=True)


def write_merged(path, tasks, pieces, per_task):
    """Writes the joined arrays to path (through a temporary file in its folder)."""
    order = list(pieces[tasks[0]].members)  # the members in the pieces' order
    total = per_task * len(tasks)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".merge.", suffix=".npz", dir=folder)
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # a file as any other, not mkstemp's private one
    try:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_STORED, allowZip64=True) as out:
            for name in order:
                shape, dtype, _ = pieces[tasks[0]].members[name]
                if name not in PER_SCENE:  # equal in every piece: the first one's, as it is
                    with zipfile.ZipFile(pieces[tasks[0]].path) as z:
                        with member(out, name) as f:
                            f.write(z.read(name + ".npy"))
                    continue
                header = {"descr": np.lib.format.dtype_to_descr(dtype), "fortran_order": False,
                          "shape": (total,) + tuple(shape[1:])}
                with member(out, name) as f:
                    np.lib.format.write_array_header_1_0(f, header)
                    for task in tasks:
                        piece = pieces[task]
                        pshape, pdtype, offset = piece.members[name]
                        size = int(np.prod(pshape, dtype=np.uint64)) * pdtype.itemsize
                        try:
                            with zipfile.ZipFile(piece.path) as z:
                                copy_member(z, name, offset, f, size)
                        except (OSError, zipfile.BadZipFile, BadPiece) as e:
                            raise BadTask(task, "task_%06d.npz: %s" % (task, e))
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def report(problems, count, run, out_dir):
    """Names each bad task and prints the sbatch command that re-runs exactly those: status 1."""
    print("merge.py: %d of %d tasks are missing or not usable; nothing written:" % (
        len(problems), count), file=sys.stderr)
    for task, problem in sorted(problems.items()):
        print("  task %d: %s" % (task, problem), file=sys.stderr)
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sample_array.sbatch")
    command = ["sbatch", "--array=" + task_ranges(sorted(problems))]
    if run.get("partition"):
        command.append("--partition=" + run["partition"])
    command += [script, run["config"], str(run["seed"]), str(run["scenes"]), out_dir]
    command += run.get("flags") or []
    print("re-run only those (with the first submission's other sbatch options), then merge "
          "again:\n  " + " ".join(shlex.quote(c) for c in command), file=sys.stderr)
    return 1


def main():
    parser = argparse.ArgumentParser(
        description="Joins the task_<T>.npz pieces of a sample_array.sbatch job into one .npz.")
    parser.add_argument("out_dir", metavar="OUT_DIR")
    parser.add_argument("merged", metavar="MERGED.npz")
    parser.add_argument("--tasks", type=int, metavar="N",
                        help="the array has tasks 0 .. N-1 (default: as its tasks recorded)")
    args = parser.parse_args()
    if not args.merged.endswith(".npz"):
        parser.error("MERGED.npz: expected a file name ending in .npz, got %r" % args.merged)
    if args.tasks is not None and args.tasks < 1:
        parser.error("--tasks: expected a positive number, got %d" % args.tasks)
    if not os.path.isdir(args.out_dir):
        parser.error("OUT_DIR: %r is not a folder" % args.out_dir)
    out_dir = os.path.abspath(args.out_dir)

    records, has_piece = load_records(out_dir)
    known = {t: r for t, r in records.items() if r is not None}
    if not known:
        print("merge.py: %s holds no task_<T>.json of sample_array.sbatch" % out_dir,
              file=sys.stderr)
        return 2
    runs = {}
    for task, record in sorted(known.items()):
        runs.setdefault(run_of(record), []).append(task)
    if len(runs) > 1:
        print("merge.py: %s holds tasks of %d different runs (configuration, its SHA-256, seed, "
              "scenes per task, flags):" % (out_dir, len(runs)), file=sys.stderr)
        for run, tasks in runs.items():
            print("  tasks %s: %s" % (task_ranges(tasks), ", ".join(
                "%s %s" % (k, v) for k, v in zip(RUN_FIELDS, run))), file=sys.stderr)
        return 2
    run = next(iter(known.values()))
    seed, per_task = int(run["seed"]), int(run["scenes"])

    last = max(list(records) + list(has_piece) +
               [r["array_task_max"] for r in known.values() if r.get("array_task_max") is not None])
    count = args.tasks if args.tasks is not None else last + 1
    if last >= count:
        print("merge.py: --tasks %d, but %s has task %d" % (count, out_dir, last), file=sys.stderr)
        return 2
    tasks = list(range(count))

    problems, pieces, reference = {}, {}, None
    for task in tasks:
        problem = problem_of(task, records.get(task), out_dir, task in has_piece)
        if problem is None:
            path = os.path.join(out_dir, "task_%06d.npz" % task)
            try:
                piece = Piece(path, task * per_task, per_task, seed)
                if reference is None:
                    reference = (task, piece)
                elif piece.layout() != reference[1].layout():
                    raise BadPiece("its arrays %s differ from task %d's %s" % (
                        piece.layout(), reference[0], reference[1].layout()))
                else:
                    for name, value in piece.constants.items():
                        if not np.array_equal(value, reference[1].constants[name]):
                            raise BadPiece("its %s %s differs from task %d's %s" % (
                                name, value.tolist(), reference[0],
                                reference[1].constants[name].tolist()))
                pieces[task] = piece
            except BadPiece as e:
                problem = "task_%06d.npz: %s" % (task, e)
            except UnknownArray as e:
                print("merge.py: task_%06d.npz: %s" % (task, e), file=sys.stderr)
                return 2
        if problem is not None:
            problems[task] = problem

    if problems:
        return report(problems, count, run, out_dir)
    try:
        write_merged(args.merged, tasks, pieces, per_task)
    except BadTask as e:
        return report({e.task: str(e)}, count, run, out_dir)
    except OSError as e:
        print("merge.py: cannot write %s: %s" % (args.merged, e), file=sys.stderr)
        return 2
    failed = sum(int(np.count_nonzero(~zipped_success(p))) for p in pieces.values())
    print("merged %d tasks: scenes 0 .. %d of seed %d (%s) into %s; %d scenes failed" % (
        count, count * per_task - 1, seed, run["config"], args.merged, failed))
    return 0


def zipped_success(piece):
    with zipfile.ZipFile(piece.path) as z:
        return Piece.read(z, "success")


if __name__ == "__main__":
    sys.exit(main())
