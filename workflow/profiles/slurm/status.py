#!/usr/bin/python3
"""Prints running, success or failed for one SLURM job id (the profile's
`cluster-status` command). Asks sacct (the job's final state survives there)
and, on clusters without accounting, scontrol (which knows a job until
MinJobAge after its end)."""
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_HOLD",
           "REQUEUE_FED", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED", "RESV_DEL_HOLD"}


def state_from_sacct(job):
    result = subprocess.run(["sacct", "-j", job, "-X", "-n", "-P", "-o", "State"], capture_output=True, text=True)
    lines = result.stdout.split()
    return lines[0].split()[0] if result.returncode == 0 and lines else None


def state_from_scontrol(job):
    result = subprocess.run(["scontrol", "show", "job", "-o", job], capture_output=True, text=True)
    for word in result.stdout.split():
        if word.startswith("JobState="):
            return word.split("=", 1)[1]
    return None


def main():
    job = sys.argv[1]
    state = state_from_sacct(job) or state_from_scontrol(job)
    if state is None:
        print(f"status.py: SLURM knows no job {job} (neither sacct nor scontrol)", file=sys.stderr)
        print("failed")
    elif state == "COMPLETED":
        print("success")
    elif state in RUNNING:
        print("running")
    else:
        print(f"status.py: SLURM job {job} ended {state}", file=sys.stderr)
        print("failed")


if __name__ == "__main__":
    main()
