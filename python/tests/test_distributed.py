"""wavejets.distributed: the tool's streamed steps as Dask tasks, on LocalClusters of this machine
(127.0.0.1 only). The outputs are compared byte for byte with the in-core run of the tool (the same
code, in this process: wavejets._wavejets._run_tool)."""

import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from conftest import ROOT

distributed = pytest.importorskip("distributed", reason="wavejets.distributed needs Dask: apt-get install python3-distributed")

from wavejets import distributed as wd  # noqa: E402
from wavejets._wavejets import _run_tool  # noqa: E402

MAKE_LARGE_PLY = Path(os.environ.get("WAVEJETS_MAKE_LARGE_PLY", ROOT / "benchmark" / "Wavejets" / "make_large_ply.py"))
TIMEOUT = 300   # seconds: every run below ends well before, or fails


def local_cluster(workers=2):
    return distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                    dashboard_address=None)


@pytest.fixture(scope="module")
def client():
    with local_cluster() as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def torus_200k(tmp_path_factory):
    """200,000 points of a bumpy torus with normals (binary PLY)."""
    path = tmp_path_factory.mktemp("torus") / "torus_200k.ply"
    subprocess.run([sys.executable, str(MAKE_LARGE_PLY), "200000", str(path)], check=True)
    return path


def in_core(command, source, out, *flags):
    status, _, err = _run_tool([command, str(source), str(out), *flags, "--quiet"])
    assert status == 0, err
    return out.read_bytes()


def no_job_left(folder):
    return not [p for p in os.listdir(folder) if p.startswith(".wavejets-job-") or ".tmp-" in p]


def run_counting_steps(*args, client, **kwargs):
    """wd.run(*args, ...): its summary, the number of tiles run, and of the tool's steps after prepare
    (tiles, parts of the output, finish or write)."""
    tiles = []
    with distributed.get_task_stream(client) as stream:
        summary = wd.run(*args, client=client, progress=False, timeout=TIMEOUT, _on_tile_done=tiles.append, **kwargs)
    steps = sum(1 for task in stream.data if task["key"].startswith("_step-"))
    return summary, len(tiles), steps


@pytest.mark.parametrize("command", ["normals", "curvature", "enhance-positions", "enhance-normals"])
def test_same_bytes_as_in_core(client, torus_200k, tmp_path, command):
    expected = in_core(command, torus_200k, tmp_path / "in_core.ply", "--k", "18")
    summary, tiles, steps = run_counting_steps(command, torus_200k, tmp_path / "out.ply", "--k", "18", client=client,
                                               tile_size=30000)
    assert (tmp_path / "out.ply").read_bytes() == expected
    assert "200000 points in input order, 200000 of them fitted" in summary
    assert no_job_left(tmp_path)
    assert steps == tiles + 3, "binary PLY in and out: the output in a part per worker (2), then finish"


def test_ascii_output_in_one_step(client, torus_200k, tmp_path):
    expected = in_core("normals", torus_200k, tmp_path / "in_core.ply", "--k", "18", "--ascii")
    summary, tiles, steps = run_counting_steps("normals", torus_200k, tmp_path / "out.ply", "--k", "18", "--ascii",
                                               client=client, tile_size=30000)
    assert (tmp_path / "out.ply").read_bytes() == expected
    assert steps == tiles + 1, "ASCII output: written by one step"


def test_three_passes_without_normals(client, kitten_path, tmp_path):
    # No input normals: estimated and oriented toward a viewpoint, enhanced, estimated again.
    bare = tmp_path / "bare.xyz"
    bare.write_text("".join(" ".join(line.split()[:3]) + "\n" for line in kitten_path.read_text().splitlines()))
    flags = ("--orient-toward", "0,0,5", "--k", "24")
    expected = in_core("enhance-positions", bare, tmp_path / "in_core.ply", *flags)
    wd.run("enhance-positions", bare, tmp_path / "out.ply", *flags, client=client, tile_size=400, progress=False,
           timeout=TIMEOUT)
    assert (tmp_path / "out.ply").read_bytes() == expected


def test_bad_input_fails_the_run(client, kitten_path, tmp_path):
    lines = kitten_path.read_text().splitlines()
    lines[1000] = "nan 0 0 0 0 1"
    bad = tmp_path / "nan.xyz"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(wd.DistributedRunError, match=r"nan\.xyz: not a valid XYZ file \(Error line 1001"):
        wd.run("normals", bad, tmp_path / "out.ply", client=client, tile_size=500, progress=False, timeout=TIMEOUT)
    assert not (tmp_path / "out.ply").exists() and no_job_left(tmp_path)


def test_corrupt_tile_input_fails_the_run(client, torus_200k, tmp_path):
    # The bins of the first pass cut short after they were written: the tiles that read past the
    # end fail, with their tile named; the run fails with that message and writes no output.
    def cut_bins(job):
        bins = Path(job) / "pass-0.bins"
        with open(bins, "r+b") as f:
            f.truncate(bins.stat().st_size // 2)
    with pytest.raises(wd.DistributedRunError, match=r"tile \d+ of pass 0: cannot read"):
        wd.run("curvature", torus_200k, tmp_path / "out.ply", "--k", "18", client=client, tile_size=30000,
               progress=False, timeout=TIMEOUT, _on_prepared=cut_bins)
    assert not (tmp_path / "out.ply").exists() and no_job_left(tmp_path)


def test_killed_worker(torus_200k, tmp_path):
    # One of two workers killed (SIGKILL) as soon as a first tile is done: Dask runs its tiles again
    # on a worker (the nanny restarts it); the output is still the in-core one.
    expected = in_core("enhance-normals", torus_200k, tmp_path / "in_core.ply", "--k", "18")
    with local_cluster() as cluster, distributed.Client(cluster) as c:
        pids = list(c.run(os.getpid).values())
        killed = []

        def kill_one(_future):
            if not killed:
                killed.append(pids[1])
                os.kill(pids[1], signal.SIGKILL)

        wd.run("enhance-normals", torus_200k, tmp_path / "out.ply", "--k", "18", client=c, tile_size=15000,
               progress=False, timeout=TIMEOUT, _on_tile_done=kill_one)
        assert killed
        assert pids[1] not in c.run(os.getpid).values()   # a new process took its place
    assert (tmp_path / "out.ply").read_bytes() == expected
    assert no_job_left(tmp_path)


def test_command_line(torus_200k, tmp_path):
    expected = in_core("normals", torus_200k, tmp_path / "in_core.ply", "--k", "18")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    p = subprocess.run([sys.executable, "-m", "wavejets.distributed", "normals", str(torus_200k), str(tmp_path / "out.ply"),
                        "--k", "18", "--workers", "2", "--tile-size", "50000"], capture_output=True, text=True, env=env,
                       timeout=TIMEOUT)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "out.ply").read_bytes() == expected
    assert "points in input order" in p.stdout and "the same bytes" not in p.stdout
    bad = subprocess.run([sys.executable, "-m", "wavejets.distributed", "normals", str(tmp_path / "missing.ply"),
                          str(tmp_path / "o.ply"), "--workers", "1"], capture_output=True, text=True, env=env, timeout=TIMEOUT)
    assert bad.returncode == 1 and "missing.ply" in bad.stderr and not (tmp_path / "o.ply").exists()


def test_arguments_checked():
    with pytest.raises(ValueError, match="command must be one of"):
        wd.run("render", "a.ply", "b.ply")
    with pytest.raises(ValueError, match="--tile-size is set by wavejets.distributed"):
        wd.run("normals", "a.ply", "b.ply", "--tile-size", "10")
