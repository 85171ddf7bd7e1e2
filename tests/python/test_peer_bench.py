"""bench/peers/compare_lulesh.py against a stand-in for LULESH (a script printing LULESH's report format and
logging its environment): the ratios are the ones the runs report, the allocator
setting reaches only the tuned runs, and a failing or malformed peer stops the script with exit 2 and no CSV."""
import csv
import os
import subprocess
import sys

import pytest

from support import REPO

SCRIPT = REPO / "bench" / "peers" / "compare_lulesh.py"

FAKE = """#!/bin/sh
echo "$(date +%s%N) GLIBC_TUNABLES=${GLIBC_TUNABLES:-none} OMP=$OMP_NUM_THREADS args=$*" >> "$FAKE_LOG"
[ -n "$FAKE_FAIL" ] && { echo "segfault, say" >&2; exit 3; }
n=$2
cat <<OUT
Running problem size $n^3 per domain until completion
Run completed:
   Problem size        =  $n
   MPI tasks           =  1
   Iteration count     =  100
   Final Origin Energy =  1.234567e+04
OUT
[ -n "$FAKE_TRUNCATE" ] && exit 0
cat <<OUT

Elapsed time         =       0.50 (s)
Grind time (us/z/c)  =  23.148148 (per dom)  ( 23.148148 overall)
FOM                  =  43.2 (z/s)
OUT
"""


@pytest.fixture
def fake(tmp_path):
    exe = tmp_path / "lulesh2.0"
    exe.write_text(FAKE)
    exe.chmod(0o755)
    return exe


def run(bin_dir, fake, tmp_path, *extra, env_extra=None):
    env = dict(os.environ, FAKE_LOG=str(tmp_path / "fake.log"), **(env_extra or {}))
    cmd = [sys.executable, str(SCRIPT), "--lulesh", str(fake), "--solid", str(bin_dir / "solid_solver"),
           "--sizes", "6", "--pairs", "2", "--csv", str(tmp_path / "pairs.csv"), "--png", str(tmp_path / "p.png"),
           *extra]
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)


def test_pairs_ratios_and_allocator_setting(bin_dir, fake, tmp_path):
    r = run(bin_dir, fake, tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    rows = list(csv.DictReader(open(tmp_path / "pairs.csv")))
    assert len(rows) == 2 * 2 * 2  # strength off/on x as built/tuned x 2 pairs
    for row in rows:
        # the stand-in reports 100 cycles of 6^3 zones in 0.5 s
        assert float(row["lulesh_zcps"]) == pytest.approx(100 * 216 / 0.5, rel=1e-4)
        assert float(row["rate_ratio"]) == pytest.approx(float(row["ours_zcps"]) / float(row["lulesh_zcps"]), rel=1e-3)
        assert float(row["tts_ratio"]) == pytest.approx(float(row["lulesh_wall_s"]) / float(row["ours_wall_s"]),
                                                        rel=2e-3)
        assert int(row["ours_steps"]) > 0 and int(row["lulesh_steps"]) == 100
    log = (tmp_path / "fake.log").read_text().splitlines()
    assert len(log) == 8
    tuned = [l for l in log if "glibc.malloc.mmap_threshold=268435456" in l]
    assert len(tuned) == 4 and all("OMP=1" in l and "args=-s 6" in l for l in log)
    # runs are grouped by (strength, variant): as built, tuned, as built, tuned
    assert [("mmap_threshold" in l) for l in log] == [False, False, True, True] * 2
    assert "shock radius" in r.stdout and (tmp_path / "p.png").stat().st_size > 1000


@pytest.mark.parametrize("env_extra, expect", [({"FAKE_FAIL": "1"}, "exited 3"),
                                               ({"FAKE_TRUNCATE": "1"}, "Elapsed time")])
def test_failing_or_malformed_peer_stops_without_csv(bin_dir, fake, tmp_path, env_extra, expect):
    r = run(bin_dir, fake, tmp_path, "--strength", "off", "--variants", "tuned", env_extra=env_extra)
    assert r.returncode == 2 and expect in r.stderr
    assert not (tmp_path / "pairs.csv").exists()


def test_bad_arguments(bin_dir, fake, tmp_path):
    r = run(bin_dir, tmp_path / "no_such_lulesh", tmp_path)
    assert r.returncode == 2 and "no_such_lulesh" in r.stderr and "not an executable" in r.stderr
    r = run(bin_dir, fake, tmp_path, "--variants", "fast")
    assert r.returncode == 2 and "--variants 'fast'" in r.stderr
