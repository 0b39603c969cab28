#!/usr/bin/python3
"""Submits one Snakemake job script with sbatch and prints the SLURM job id
(the profile's `cluster` command: Snakemake appends the job script).

sbatch options from the job's resources: gpus -> --gres=gpu:N (none when 0,
e.g. on a test cluster without GPUs), runtime (minutes) -> --time, mem_mb ->
--mem, threads -> --cpus-per-task, slurm_partition, slurm_account,
constraint (e.g. a GPU type, so that every shard runs on the same model) and
slurm_extra (more sbatch words). Logs: .snakemake/slurm_logs/ in the
working directory."""
import os
import shlex
import subprocess
import sys

from snakemake.utils import read_job_properties


def sbatch_arguments(properties, log_directory):
    resources = properties.get("resources", {})
    arguments = ["sbatch", "--parsable", f"--job-name=oitbench-{properties.get('rule', 'job')}",
                 f"--output={log_directory}/%x-%j.log", f"--cpus-per-task={properties.get('threads', 1)}"]
    if int(resources.get("gpus", 0)) > 0:
        arguments.append(f"--gres=gpu:{int(resources['gpus'])}")
    for resource, option in (("runtime", "--time"), ("mem_mb", "--mem"), ("slurm_partition", "--partition"),
                             ("slurm_account", "--account"), ("constraint", "--constraint")):
        if resources.get(resource):
            arguments.append(f"{option}={resources[resource]}")
    arguments += shlex.split(str(resources.get("slurm_extra", "")))
    return arguments


def main():
    jobscript = sys.argv[-1]
    log_directory = os.path.join(os.getcwd(), ".snakemake", "slurm_logs")
    os.makedirs(log_directory, exist_ok=True)
    arguments = sbatch_arguments(read_job_properties(jobscript), log_directory) + [jobscript]
    result = subprocess.run(arguments, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"submit.py: {shlex.join(arguments)} failed ({result.returncode}): {result.stderr.strip()}")
    print(result.stdout.strip().split(";")[0])


if __name__ == "__main__":
    main()
