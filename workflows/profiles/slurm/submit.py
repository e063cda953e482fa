#!/usr/bin/env python3
"""Submits one Snakemake job (a single rule's job or a group job) to Slurm with sbatch; prints the Slurm job id.

Snakemake's generic cluster executor calls this with the job script as the only argument. The job asks for the
threads, memory (mem_mb) and run time (minutes) the Snakefile states; a group job for what Snakemake computed for the
group (the largest memory and threads of its steps, their run times added). The job's name is
lfsp:<rules>:<wildcards> (e.g. lfsp:decode,depth,segment,report:a-capture), so that squeue, sacct and the job
completion log say which rules ran for which captures. Its Slurm log goes to slurm-logs/<job id>.out under the working
directory. Site options (partition, account, QOS, ...) come from the environment variable LFSP_SBATCH_OPTIONS, e.g.
LFSP_SBATCH_OPTIONS="--partition=short --account=lab42"."""

import json
import os
import re
import shlex
import subprocess
import sys

PIPELINE = ("decode", "depth", "segment", "report", "hci_submission", "depth_score", "index")  # names in this order
MAX_NAME = 200  # characters of a job name kept (Slurm allows more; squeue and sacct columns do not)


def job_name(properties, jobscript):
    """lfsp:<rules>:<wildcard values>; a group job's rules and wildcards are its --target-jobs (rule:key=value,...)."""
    if properties["type"] == "single":
        rules = [properties["rule"]]
        values = list(properties.get("wildcards", {}).values())
    else:
        with open(jobscript) as script:
            text = script.read()
        targets = re.search(r"--target-jobs ((?:'[^']*' ?)+)", text)
        rules, values = [], []
        for target in shlex.split(targets.group(1)) if targets else []:
            rule, _, wildcards = target.partition(":")
            rules.append(rule)
            values += [pair.partition("=")[2] for pair in wildcards.split(",") if pair]
        rules = rules or [properties["groupid"]]
    rules = sorted(set(rules), key=lambda rule: (PIPELINE.index(rule) if rule in PIPELINE else len(PIPELINE), rule))
    values = list(dict.fromkeys(values))
    name = f"lfsp:{','.join(rules)}:{','.join(values)}".rstrip(":")
    return name if len(name) <= MAX_NAME else name[: MAX_NAME - 3] + "..."


def read_job_properties(jobscript):
    """The job's properties, from the "# properties = {...}" line Snakemake writes into every job script (what
    snakemake.utils.read_job_properties reads; Debian's snakemake is not importable from a plain python3)."""
    with open(jobscript) as script:
        for line in script:
            if line.startswith("# properties = "):
                return json.loads(line[len("# properties = "):])
    sys.exit(f"submit.py: {jobscript}: no '# properties = ' line")


def main():
    jobscript = sys.argv[-1]
    properties = read_job_properties(jobscript)
    resources = properties.get("resources", {})
    os.makedirs("slurm-logs", exist_ok=True)
    command = ["sbatch", "--parsable", f"--job-name={job_name(properties, jobscript)}",
               f"--cpus-per-task={properties.get('threads', 1)}", "--output=slurm-logs/%j.out"]
    if "mem_mb" in resources:
        command.append(f"--mem={resources['mem_mb']}M")
    if "runtime" in resources:
        command.append(f"--time={resources['runtime']}")
    command += shlex.split(os.environ.get("LFSP_SBATCH_OPTIONS", ""))
    command.append(jobscript)
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"submit.py: {' '.join(command)}: {result.stderr.strip()}")
    print(result.stdout.strip().split(";")[0])  # --parsable prints <id> or <id>;<cluster>


if __name__ == "__main__":
    main()
