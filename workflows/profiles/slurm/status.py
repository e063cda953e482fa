#!/usr/bin/env python3
"""Prints the state of one Slurm job for Snakemake's --cluster-status: running, success or failed.

Asks the controller first (scontrol knows a job until MinJobAge after it ends), then the accounting (sacct, on
clusters with slurmdbd), then the job completion log (sacct --completion, clusters with JobCompType but no
accounting database, such as lfsp's test cluster). A job no source knows is failed; a controller that does not
answer (busy, restarting) leaves the job running, to be asked again."""

import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_FED", "REQUEUE_HOLD",
           "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED", "RESV_DEL_HOLD", "SPECIAL_EXIT"}


def verdict(state):
    state = state.split()[0].rstrip("+") if state.strip() else ""
    if not state:
        return None
    if state == "COMPLETED":
        return "success"
    return "running" if state in RUNNING else "failed"  # FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY, NODE_FAIL, ...


def run(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None


def main():
    job = sys.argv[1]
    shown = run(["scontrol", "show", "job", "--oneliner", job])
    if shown is None:
        print("running")
        return
    if shown.returncode == 0:
        for field in shown.stdout.split():
            if field.startswith("JobState="):
                print(verdict(field.partition("=")[2]) or "running")
                return
    elif "Invalid job id" not in shown.stderr:
        print("running")  # the controller did not answer: ask again later
        return
    for source in (["sacct"], ["sacct", "--completion"]):
        listed = run(source + ["-j", job, "-X", "-n", "-P", "-o", "State"])
        if listed is not None and listed.returncode == 0:
            state = verdict(listed.stdout.strip().splitlines()[-1] if listed.stdout.strip() else "")
            if state:
                print(state)
                return
    print("failed")


if __name__ == "__main__":
    try:
        main()
        sys.stdout.flush()
    except BrokenPipeError:
        # Snakemake stopped listening (it is shutting down, or timed the call out): no answer is wanted, and a
        # traceback in its log would read as a failure. Point stdout at /dev/null so the exit flush is quiet too.
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        sys.exit(1)
