"""A real single-node Slurm cluster on this machine, for the farm tests and measurements: munged,
slurmctld and slurmd (Debian's munge and slurm-wlm, scripts/install_deps.sh), run as root with every
file of theirs (configuration, munge key, state, logs, sockets) in one throw-away folder.

    with Cluster(folder, cpus=2) as cluster:      # started, or ClusterError saying why not
        subprocess.run(["sbatch", ...], env=cluster.env)
    # stopped: jobs cancelled, the three daemons ended

    python3 tests/farm/slurm_cluster.py FOLDER -- COMMAND...   runs COMMAND with the cluster up
                                                              (SLURM_CONF set), then stops it

The node is this host (NodeAddr 127.0.0.1), SlurmUser root, proctrack/linuxproc and task/none (no
cgroups needed), select/cons_tres by core, no accounting. The daemons run in the foreground as this
process's children, so stop() ends exactly them.
"""

import os
import shutil
import signal
import socket
import subprocess
import sys
import time

START_TIMEOUT = 60.0  # seconds for the daemons to answer and the node to be idle
STOP_TIMEOUT = 20.0
COMMAND_TIMEOUT = 15.0  # seconds for one sinfo or squeue (Slurm's clients wait 10 s for an answer)
DAEMONS = ("munged", "slurmctld", "slurmd")


class ClusterError(RuntimeError):
    pass


def _free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _program(name):
    for folder in (None, "/usr/sbin", "/sbin"):
        found = shutil.which(name, path=folder)
        if found:
            return found
    raise ClusterError("%s is not installed: Slurm tests need Debian's slurm-wlm and munge "
                       "(bash scripts/install_deps.sh installs them)" % name)


def _tail(path, lines=15):
    try:
        with open(path, errors="replace") as handle:
            return "".join(handle.readlines()[-lines:])
    except OSError:
        return "(no log)\n"


class Cluster:
    def __init__(self, folder, cpus=2, memory_mb=4000):
        self.folder = os.path.abspath(folder)
        self.cpus, self.memory_mb = cpus, memory_mb
        self.host = socket.gethostname().split(".")[0]
        self.conf = os.path.join(self.folder, "slurm.conf")
        self.socket = os.path.join(self.folder, "munge", "munge.socket")
        self.processes = {}
        self.env = dict(os.environ, SLURM_CONF=self.conf)

    def path(self, *parts):
        return os.path.join(self.folder, *parts)

    # -- start ---------------------------------------------------------------------------

    def start(self):
        if os.geteuid() != 0:
            raise ClusterError("the single-node Slurm cluster runs its daemons as root (SlurmUser=root); "
                               "this process runs as uid %d" % os.geteuid())
        programs = {name: _program(name) for name in DAEMONS + ("sbatch", "scontrol", "sinfo")}
        for sub in ("munge", "state", "spool", "logs"):
            os.makedirs(self.path(sub), exist_ok=True)
        os.chmod(self.path("munge"), 0o700)  # munged refuses a socket folder others may write to
        try:
            self._start_munge(programs["munged"])
            self._write_conf()
            self._spawn("slurmctld", [programs["slurmctld"], "-D", "-c", "-f", self.conf])
            self._spawn("slurmd", [programs["slurmd"], "-D", "-f", self.conf, "-N", self.host])
            self._wait_idle()
        except BaseException:
            self.stop()
            raise
        return self

    def _start_munge(self, munged):
        key = self.path("munge", "munge.key")
        mungekey = shutil.which("mungekey", path="/usr/sbin:/usr/bin:/sbin")
        if mungekey:
            subprocess.run([mungekey, "--create", "--keyfile", key], check=True, capture_output=True)
        else:
            with open(key, "wb") as handle:
                handle.write(os.urandom(1024))
        os.chmod(key, 0o600)
        self._spawn("munged", [munged, "-F", "--force", "--key-file", key, "--socket", self.socket,
                               "--pid-file", self.path("munge", "munged.pid"),
                               "--log-file", self.path("logs", "munged.log"),
                               "--seed-file", self.path("munge", "munged.seed")])
        deadline = time.monotonic() + 10.0
        while not os.path.exists(self.socket):
            self._check_alive()
            if time.monotonic() > deadline:
                raise ClusterError("munged did not open its socket %s within 10 s:\n%s"
                                   % (self.socket, _tail(self.path("logs", "munged.log"))))
            time.sleep(0.1)

    def _write_conf(self):
        ctld_port, slurmd_port = _free_port(), _free_port()
        lines = [
            "ClusterName=gaussfarm",
            "SlurmctldHost=%s(127.0.0.1)" % self.host,
            "SlurmctldPort=%d" % ctld_port,
            "SlurmdPort=%d" % slurmd_port,
            "SlurmUser=root",
            "SlurmdUser=root",
            "AuthType=auth/munge",
            "CredType=cred/munge",
            "AuthInfo=socket=%s" % self.socket,
            "MpiDefault=none",
            "ProctrackType=proctrack/linuxproc",
            "TaskPlugin=task/none",
            "JobAcctGatherType=jobacct_gather/none",
            "AccountingStorageType=accounting_storage/none",
            "JobCompType=jobcomp/none",
            "SchedulerType=sched/backfill",
            "SelectType=select/cons_tres",
            "SelectTypeParameters=CR_Core",
            "ReturnToService=2",
            "MinJobAge=600",
            "SlurmctldTimeout=30",
            "SlurmdTimeout=30",
            "StateSaveLocation=%s" % self.path("state"),
            "SlurmdSpoolDir=%s" % self.path("spool"),
            "SlurmctldPidFile=%s" % self.path("slurmctld.pid"),
            "SlurmdPidFile=%s" % self.path("slurmd.pid"),
            "SlurmctldLogFile=%s" % self.path("logs", "slurmctld.log"),
            "SlurmdLogFile=%s" % self.path("logs", "slurmd.log"),
            "NodeName=%s NodeAddr=127.0.0.1 CPUs=%d RealMemory=%d State=UNKNOWN"
            % (self.host, self.cpus, self.memory_mb),
            "PartitionName=farm Nodes=%s Default=YES MaxTime=INFINITE State=UP" % self.host,
        ]
        with open(self.conf, "w") as handle:
            handle.write("\n".join(lines) + "\n")

    def _spawn(self, name, argv):
        log = open(self.path("logs", name + ".out"), "wb")
        self.processes[name] = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                                env=self.env, start_new_session=True)
        log.close()

    def _check_alive(self):
        for name, process in self.processes.items():
            if process.poll() is not None:
                raise ClusterError("%s exited with status %d while starting:\n%s%s"
                                   % (name, process.returncode, _tail(self.path("logs", name + ".out")),
                                      _tail(self.path("logs", name + ".log"))))

    def _wait_idle(self):
        deadline = time.monotonic() + START_TIMEOUT
        state = ""
        while time.monotonic() < deadline:
            self._check_alive()
            try:
                result = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], capture_output=True, text=True,
                                        env=self.env, stdin=subprocess.DEVNULL, timeout=COMMAND_TIMEOUT)
            except subprocess.TimeoutExpired:
                state = "sinfo did not answer within %.0f s" % COMMAND_TIMEOUT
                continue
            state = (result.stdout + result.stderr).strip()
            if result.returncode == 0 and state.rstrip("*") == "idle":
                return
            time.sleep(0.5)
        raise ClusterError("the Slurm node was not idle within %.0f s (sinfo: %r)\nslurmctld:\n%s\nslurmd:\n%s"
                           % (START_TIMEOUT, state, _tail(self.path("logs", "slurmctld.log")),
                              _tail(self.path("logs", "slurmd.log"))))

    # -- stop ----------------------------------------------------------------------------

    def stop(self):
        """Cancel every job of this cluster, then end the daemons (slurmd, slurmctld, munged)."""
        if "slurmctld" in self.processes and self.processes["slurmctld"].poll() is None:
            try:
                subprocess.run(["scancel", "--full", "--user", "root"], env=self.env, capture_output=True,
                               stdin=subprocess.DEVNULL, timeout=STOP_TIMEOUT)
            except subprocess.TimeoutExpired:
                pass  # the daemons are ended below all the same
            deadline = time.monotonic() + STOP_TIMEOUT
            while time.monotonic() < deadline:
                try:
                    result = subprocess.run(["squeue", "-h"], env=self.env, capture_output=True, text=True,
                                            stdin=subprocess.DEVNULL, timeout=COMMAND_TIMEOUT)
                except subprocess.TimeoutExpired:
                    break  # the daemons are ended below all the same
                if result.returncode != 0 or not result.stdout.strip():
                    break
                time.sleep(0.5)
        for name in reversed(DAEMONS):
            process = self.processes.get(name)
            if process is None or process.poll() is not None:
                continue
            process.send_signal(signal.SIGTERM)
            try:
                process.wait(STOP_TIMEOUT)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def running(self):
        """The daemons this cluster started that are still running."""
        return [name for name, process in self.processes.items() if process.poll() is None]

    def __enter__(self):
        return self.start()

    def __exit__(self, *_exc):
        self.stop()


def main(argv):
    if "--" not in argv or argv.index("--") != 1 or len(argv) < 3:
        sys.exit(__doc__)
    with Cluster(argv[0]) as cluster:
        return subprocess.run(argv[2:], env=cluster.env).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
