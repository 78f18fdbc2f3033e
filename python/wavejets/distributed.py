"""Point sets larger than one machine: a command of the `wavejets` tool, tile by tile, on Dask.

``run("normals", "scan.ply", "out.ply", "--k", "18")`` runs what ``wavejets normals scan.ply
out.ply --k 18 --max-memory 2G`` runs, in steps that are Dask tasks: reading and binning the input,
then every tile of every pass (independent tasks, spread over the workers), then writing OUT (in a
part per worker, for binary output of a binary PLY). OUT
is the in-core run's file, byte for byte, however many workers and whatever fails and is run again.

The files (IN, OUT and a job folder of scratch files created next to OUT, removed at the end) must
be reachable by every worker at the same paths: one machine, or a shared file system. Relative paths
are taken from the caller's working directory, which the workers must also reach.

With no cluster given, a ``distributed.LocalCluster`` of worker processes (one thread each, one per
core, on 127.0.0.1) is started for the run and closed after it. Pass ``client=`` (a
``distributed.Client``) or ``scheduler=`` (its address) to use a cluster of many machines.

From a shell::

    python3 -m wavejets.distributed normals scan.ply out.ply --k 18 [--workers N | --scheduler ADDRESS]

Needs Dask and distributed (Debian: python3-dask, python3-distributed).
"""

import os
import shutil
import sys
import tempfile
import threading
import time

from ._wavejets import _keep_freed_memory_for_reuse, _run_tool

__all__ = ["run", "main"]

COMMANDS = ("normals", "curvature", "enhance-positions", "enhance-normals")
_WRITE_PART_POINTS = 1 << 16   # the least points of a part of the output written by one worker


class DistributedRunError(RuntimeError):
    """A step of a distributed run failed: the tool's error message (e.g. a malformed input)."""


def _worker_threads():
    """Threads this task may use: those of its worker (1 in the default cluster)."""
    try:
        from distributed import get_worker
        worker = get_worker()
        state = getattr(worker, "state", None)   # distributed 2022.08 and later
        return max(1, int(state.nthreads if state is not None else worker.nthreads))
    except Exception:   # not in a worker (a step run in the caller's process)
        return os.cpu_count() or 1


def _has_bokeh():
    """Dask's dashboard needs bokeh (Debian: python3-bokeh); without it, no dashboard."""
    try:
        import bokeh  # noqa: F401
        return True
    except ImportError:
        return False


_chdir_lock = threading.Lock()


def _step(args, stage, cwd):
    """One step of the run in a worker: the tool with --stage STAGE; the tool's output, or an error."""
    argv = list(args) + ["--stage", stage, "--threads", str(_worker_threads())]
    if stage != "write" and not stage.startswith("finish:"):
        argv.append("--quiet")
    _keep_freed_memory_for_reuse()   # the worker runs the tool's steps, buffers of megabytes each
    with _chdir_lock:   # relative paths are the caller's (the tool runs one call at a time anyway)
        previous = os.getcwd()
        os.chdir(cwd)
        try:
            status, out, err = _run_tool(argv)
        finally:
            os.chdir(previous)
    if status != 0:
        message = err.strip().splitlines()[-1] if err.strip() else "exit status %d" % status
        if message.startswith("wavejets: error: "):
            message = message[len("wavejets: error: "):]
        raise DistributedRunError(message)
    return out


def _read_number(path, key=None):
    """The number on the line of `key` (or on the first line) of a small text file of the job."""
    with open(path) as f:
        for line in f:
            words = line.split()
            if key is None and words:
                return int(words[0])
            if len(words) == 2 and words[0] == key:
                return int(words[1])
    raise DistributedRunError("%s: no %s" % (path, key or "number"))


def _tiles_largest_first(job, p):
    """The tiles of pass `p`, the largest first: Dask runs them in this order, so that the last ones
    to run, while other workers may have nothing left to do, are the smallest."""
    path = os.path.join(job, "pass-%d.tiles" % p)
    with open(path) as f:
        numbers = [int(w) for w in f.read().split()]
    if not numbers or len(numbers) != numbers[0] + 1:
        raise DistributedRunError("%s: not a list of tiles" % path)
    return sorted(range(numbers[0]), key=lambda t: -numbers[1 + t])


# The steps below run in a worker and return what the client needs to know of the job's files:
# the client reads none of them itself.
def _prepare(args, cwd, job):
    _step(args, "prepare", cwd)
    description = os.path.join(job, "run")
    return (_read_number(description, "passes"), _tiles_largest_first(job, 0),
            _read_number(description, "points"), _read_number(description, "write_in_parts"))


def _bin(args, cwd, job, p):
    _step(args, "bin:%d" % p, cwd)
    return _tiles_largest_first(job, p)


def _remove_job(job, timeout):
    """Removes the job folder; a cancelled tile still running may write a file there meanwhile (its
    last write fails once the folder is gone): try again until it is gone."""
    deadline = time.monotonic() + (timeout or 600)
    while True:
        shutil.rmtree(job, ignore_errors=True)
        if not os.path.exists(job) or time.monotonic() > deadline:
            return
        time.sleep(0.2)


def run(command, input, output, *flags, client=None, scheduler=None, workers=None, tile_size=None,
        max_memory=None, progress=True, timeout=None, _on_prepared=None, _on_tile_done=None):
    """Runs `wavejets COMMAND INPUT OUTPUT FLAGS...` as Dask tasks; returns the tool's summary.

    `flags` are the tool's flags as strings (``"--k", "18"``). The tiles hold at most `tile_size`
    points, or as many as fit in `max_memory` (e.g. ``"2G"``: a tile's memory, in each worker);
    default 2G. `client`: a ``distributed.Client``; `scheduler`: the address of a scheduler to
    connect to; else a LocalCluster of `workers` processes (default: one per core) for this run.
    `progress`: Dask's progress bar. `timeout`: seconds to wait for each step (or pass) before
    giving up (TimeoutError). Raises DistributedRunError with the tool's message when a step fails
    (no OUT is written then), ValueError for an unknown command or a flag that is set here.
    """
    if command not in COMMANDS:
        raise ValueError("command must be one of %s, not %r" % (", ".join(COMMANDS), command))
    flags = [str(f) for f in flags]
    for f in ("--job", "--stage", "--threads", "--max-memory", "--tile-size"):
        if f in flags:
            raise ValueError("%s is set by wavejets.distributed (use tile_size= or max_memory=)" % f)
    if tile_size is not None and max_memory is not None:
        raise ValueError("give tile_size or max_memory, not both")
    size = ["--tile-size", str(int(tile_size))] if tile_size is not None else ["--max-memory", str(max_memory or "2G")]
    from distributed import Client, LocalCluster, progress as dask_progress, wait

    own_cluster = None
    if client is None:
        if scheduler is not None:
            client = Client(scheduler)
        else:
            own_cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address="127.0.0.1:0" if _has_bokeh() else None)
            client = Client(own_cluster)
    owned_client = client if (own_cluster is not None or scheduler is not None) else None
    cwd = os.getcwd()
    folder = os.path.dirname(os.path.abspath(output))
    job = tempfile.mkdtemp(prefix=".wavejets-job-", dir=folder)
    args = [command, str(input), str(output)] + flags + size + ["--job", job]
    futures = []
    try:
        if progress and client.dashboard_link:
            print("wavejets.distributed: Dask dashboard at %s" % client.dashboard_link, file=sys.stderr)
        passes, tiles, points, in_parts = client.submit(_prepare, args, cwd, job, pure=False).result(timeout)
        if _on_prepared is not None:
            _on_prepared(job)
        for p in range(passes):
            if p > 0:
                tiles = client.submit(_bin, args, cwd, job, p, pure=False).result(timeout)
            futures = client.map(_step, [args] * len(tiles), ["tile:%d:%d" % (p, t) for t in tiles],
                                 [cwd] * len(tiles), pure=False)
            if _on_tile_done is not None:
                for fut in futures:
                    fut.add_done_callback(_on_tile_done)
            if progress:
                print("wavejets.distributed: pass %d of %d, %d tiles" % (p + 1, passes, len(tiles)), file=sys.stderr)
                dask_progress(futures)
                print(file=sys.stderr)
            wait(futures, timeout=timeout)
            client.gather(futures)   # raises the first failed tile's error
        # OUT: in one step, or (binary output of a binary PLY) in a part per worker, each part at its
        # place in the file, then the header.
        parts = min(len(client.scheduler_info()["workers"]), points // _WRITE_PART_POINTS) if in_parts else 0
        if parts < 2:
            return client.submit(_step, args, "write", cwd, pure=False).result(timeout)
        futures = client.map(_step, [args] * parts, ["write:%d:%d" % (c, parts) for c in range(parts)], [cwd] * parts,
                             pure=False)
        wait(futures, timeout=timeout)
        client.gather(futures)
        return client.submit(_step, args, "finish:%d" % parts, cwd, pure=False).result(timeout)
    except BaseException:
        client.cancel(futures)   # the other tiles of a failed pass: nothing is left running on the job folder
        raise
    finally:
        _remove_job(job, timeout)
        if owned_client is not None:
            owned_client.close()
        if own_cluster is not None:
            own_cluster.close()


def main(argv=None):
    """python3 -m wavejets.distributed COMMAND IN OUT [the tool's flags] [--workers N | --scheduler ADDRESS]
    [--tile-size N | --max-memory SIZE]"""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.split("\n\n")[0] + "\n\nusage: python3 -m wavejets.distributed COMMAND IN OUT [flags of "
              "`wavejets COMMAND --help`] [--workers N | --scheduler ADDRESS] [--tile-size N | --max-memory SIZE]\n"
              "  --workers N          a LocalCluster of N worker processes on this machine (default: one per core)\n"
              "  --scheduler ADDRESS  run on the Dask cluster of this scheduler (e.g. tcp://10.0.0.1:8786)")
        return 0
    options = {}
    rest = []
    i = 0
    while i < len(argv):
        a = argv[i]
        key = {"--workers": "workers", "--scheduler": "scheduler", "--tile-size": "tile_size",
               "--max-memory": "max_memory"}.get(a.split("=")[0])
        if key is None:
            rest.append(a)
            i += 1
            continue
        if "=" in a:
            value = a.split("=", 1)[1]
            i += 1
        elif i + 1 < len(argv):
            value = argv[i + 1]
            i += 2
        else:
            print("wavejets.distributed: error: %s needs a value" % a, file=sys.stderr)
            return 2
        options[key] = int(value) if key in ("workers", "tile_size") else value
    if len(rest) < 3:
        print("wavejets.distributed: error: expected COMMAND IN OUT (--help)", file=sys.stderr)
        return 2
    quiet = "-q" in rest or "--quiet" in rest
    try:
        summary = run(rest[0], rest[1], rest[2], *rest[3:], progress=not quiet, **options)
    except (DistributedRunError, ValueError) as e:
        print("wavejets.distributed: error: %s" % e, file=sys.stderr)
        return 1
    if summary:
        print(summary.strip())
    return 0


if __name__ == "__main__":
    # Through the imported module, not __main__: Dask pickles the tasks' functions by reference to
    # wavejets.distributed (the workers import it), not by value.
    from wavejets.distributed import main as _main
    sys.exit(_main())
