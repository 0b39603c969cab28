#!/usr/bin/python3
"""The Snakemake workflow (workflow/) on this machine and on a real
single-node SLURM cluster started here: munged, slurmctld and slurmd from a
slurm.conf generated in a temporary directory, always stopped at the end. A
small sweep file goes through `snakemake -j 2` and through the SLURM profile
(each shard an sbatch job); the merged CSVs must hold exactly the same rows,
timings aside, with no run twice, and a shard run again resumes instead of
adding rows.

Usage: workflow_slurm_test.py OITBENCH (CTest passes the built binary)."""
import csv
import ctypes
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OITBENCH = os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else os.path.join(REPO, "build", "harness",
                                                                                        "oitbench")
# What the viewer's "Add this configuration to the sweep file" writes, plus a
# swept line: 4 bench invocations, 2 shards of 2.
SWEEP = """# a comment line, as the viewer writes one
oitbench bench --technique unsorted --technique linked_list --scene quads --scene-set layers=4 --size 32x32 \
--warmup 0 --frames 1 --csv oitbench_sweep.csv
oitbench bench --technique kbuffer --set k=2,4 --scene quads --scene-set layers=4 --size 32x32 --warmup 0 \
--frames 1 --csv oitbench_sweep.csv
oitbench bench --technique depth_peeling --scene quads --size 24x16 --camera random:2:1 --warmup 0 --frames 1 \
--csv oitbench_sweep.csv
oitbench bench --technique weighted_blended --scene torus --scene-set slices=8 --scene-set stacks=4 --size 32x32 \
--warmup 0 --frames 1 --csv oitbench_sweep.csv
"""
PR_SET_PDEATHSIG = 1  # <sys/prctl.h>
# Columns that differ between two runs of the same configuration.
# Differ between two recordings of the same runs: timings, and the run id
# (random per bench process).
TIMING = {"timestamp", "median_ms", "min_ms", "p05_ms", "p95_ms", "mean_ms", "other_cpu_load", "noisy",
          "clock_disagreement", "run_id",
          # How long a run went on and what its frames showed depend on the host's speed and load too.
          "frames", "warmup", "ci_low_ms", "ci_high_ms", "precision_reached", "rounds", "ratio", "ratio_ci_low",
          "ratio_ci_high", "warnings", "frame_overhead_ms", "gpu_sm_mhz_start", "gpu_sm_mhz_end",
          "gpu_mem_mhz_start", "gpu_mem_mhz_end", "gpu_temp_c_end", "samples_ms"}
RUN_KEY = ["technique", "params", "scene", "scene_params", "camera", "width", "height", "scene_rect", "clock",
           "stage", "device", "platform"]


def die_with_parent():
    """The daemons get SIGTERM when this test process dies, even by SIGKILL
    (a CTest timeout): no cluster outlives its test."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(what, condition, seconds):
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            raise TimeoutError(f"{what} not ready after {seconds} s")
        time.sleep(0.2)


class SlurmCluster:
    """munged, slurmctld and slurmd on localhost, everything under `root`."""

    def __init__(self, root):
        self.root = root
        self.processes = []
        self.conf = os.path.join(root, "slurm.conf")
        self.env = dict(os.environ, SLURM_CONF=self.conf)

    def start(self):
        os.makedirs(self.root)
        key_dir, socket_dir = os.path.join(self.root, "munge_key"), os.path.join(self.root, "munge_socket")
        os.mkdir(key_dir, 0o700)
        os.mkdir(socket_dir, 0o755)  # munged wants its socket's directory open to all
        key = os.path.join(key_dir, "munge.key")
        subprocess.run(["mungekey", "--create", "--keyfile", key], check=True)
        self.munge_socket = os.path.join(socket_dir, "munge.socket")
        self.spawn("munged", ["munged", "--foreground", f"--socket={self.munge_socket}", f"--key-file={key}",
                              f"--pid-file={key_dir}/munged.pid", f"--seed-file={key_dir}/munged.seed",
                              f"--log-file={self.root}/munged.log"])
        wait_for("munged", lambda: self.alive() and os.path.exists(self.munge_socket), 10)
        for directory in ("state", "spool"):
            os.mkdir(os.path.join(self.root, directory))
        with open(self.conf, "w") as f:
            f.write(self.slurm_conf())
        self.spawn("slurmctld", ["slurmctld", "-D", "-f", self.conf])
        self.spawn("slurmd", ["slurmd", "-D", "-N", "localhost", "-f", self.conf])
        wait_for("the SLURM node", self.node_idle, 30)

    def slurm_conf(self):
        r = self.root
        return f"""ClusterName=oitbench-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.munge_socket}
StateSaveLocation={r}/state
SlurmdSpoolDir={r}/spool
SlurmctldPidFile={r}/slurmctld.pid
SlurmdPidFile={r}/slurmd.pid
SlurmctldLogFile={r}/slurmctld.log
SlurmdLogFile={r}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=sched_interval=1
ReturnToService=2
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 RealMemory=2000 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
"""

    def spawn(self, name, command):
        log = open(os.path.join(self.root, f"{name}.out"), "w")
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=self.env,
                                   preexec_fn=die_with_parent)
        self.processes.append((name, process))
        log.close()

    def alive(self):
        for name, process in self.processes:
            if process.poll() is not None:
                raise RuntimeError(f"{name} exited with {process.returncode}: {self.log(name)}")
        return True

    def node_idle(self):
        self.alive()
        result = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True, env=self.env)
        return result.returncode == 0 and result.stdout.strip() == "idle"

    def log(self, name):
        path = os.path.join(self.root, f"{name}.out")
        with open(path) as f:
            return f.read()[-2000:]

    def stop(self):
        for _, process in reversed(self.processes):
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
        for _, process in self.processes:
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def without_timings(rows):
    return sorted(tuple((k, v) for k, v in sorted(r.items()) if k not in TIMING) for r in rows)


class WorkflowSlurmTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="oitbench-workflow-")
        os.chmod(cls.tmp, 0o755)  # munged wants every directory above its socket open to all
        cls.sweep = os.path.join(cls.tmp, "my_sweep.txt")
        with open(cls.sweep, "w") as f:
            f.write(SWEEP)
        cls.config = os.path.join(cls.tmp, "config.yaml")
        with open(cls.config, "w") as f:
            f.write(f"out: results\noitbench: {OITBENCH}\nreproduce: none\nsweep_files: [{cls.sweep}]\n"
                    "benches_per_shard: 2\nruntime_minutes: 10\nmem_mb: 500\n")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def snakemake(self, directory, *arguments, env=None):
        os.makedirs(directory, exist_ok=True)
        command = ["/usr/bin/python3", "-m", "snakemake", "--snakefile", os.path.join(REPO, "workflow", "Snakefile"),
                   "--configfile", self.config, *arguments]
        result = subprocess.run(command, cwd=directory, capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 0, f"{' '.join(command)}\n{result.stdout}\n{result.stderr[-6000:]}")
        return result

    def test_slurm_run_merges_the_same_rows_as_the_local_run(self):
        local = os.path.join(self.tmp, "local")
        self.snakemake(local, "-j", "2")
        local_rows = read_rows(os.path.join(local, "results", "my_sweep.csv"))
        self.assertTrue(os.path.getsize(os.path.join(local, "results", "my_sweep_stages.png")) > 0)
        # 4 invocations: 2 + 2 (k=2,4) + 2 (views) + 1 runs, every one ok.
        runs = {tuple(r[c] for c in ("technique", "params", "scene", "scene_params", "camera", "width", "height"))
                for r in local_rows}
        self.assertEqual(len(runs), 7, runs)
        self.assertEqual({r["status"] for r in local_rows}, {"ok"})
        keys = [tuple(r[c] for c in RUN_KEY) for r in local_rows]
        self.assertEqual(len(keys), len(set(keys)), "a run recorded twice")

        # Resume: a shard whose job must run again appends nothing.
        shard_dir = os.path.join(local, "results", "shards", "my_sweep")
        done = sorted(f for f in os.listdir(shard_dir) if f.endswith(".done"))
        self.assertEqual(len(done), 2)
        os.remove(os.path.join(shard_dir, done[0]))
        self.snakemake(local, "-j", "2")
        self.assertEqual(read_rows(os.path.join(local, "results", "my_sweep.csv")), local_rows)

        cluster = SlurmCluster(os.path.join(self.tmp, "slurm_cluster"))
        try:
            cluster.start()
            # CI=true: Snakemake polls its cluster jobs every second instead of every ten.
            env = dict(cluster.env, CI="true")
            slurm = os.path.join(self.tmp, "slurm")
            self.snakemake(slurm, "--profile", os.path.join(REPO, "workflow", "profiles", "slurm"),
                           "--config", "gpus_per_job=0", env=env)
            jobs = subprocess.run(["squeue", "-h", "-t", "all", "-o", "%j %T"], capture_output=True, text=True,
                                  env=cluster.env, check=True).stdout.split("\n")
        finally:
            cluster.stop()
        self.assertEqual(sorted(j for j in jobs if j), ["oitbench-shard COMPLETED"] * 2)
        slurm_rows = read_rows(os.path.join(slurm, "results", "my_sweep.csv"))
        self.assertEqual(without_timings(slurm_rows), without_timings(local_rows))


if __name__ == "__main__":
    unittest.main()
