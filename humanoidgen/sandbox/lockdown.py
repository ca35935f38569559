"""The operating system's part of the plan worker: what a locked-down process may still do.

`lock_down()` is called once in a fresh worker process, before any thread is started and before any plan
code runs. It cannot be undone (no-new-privileges is set, seccomp filters and Landlock rulesets only ever
narrow). What it does, in order:

1. resource limits: address space, CPU seconds, no core files, no file may grow past 0 bytes
   (RLIMIT_FSIZE), no nice or real-time priority to raise to, and the hard limits equal the soft ones;
   then a fresh IPC namespace where the kernel allows one (optional: step 3 refuses IPC in any case);
2. Landlock (kernel >= 5.13): the file system becomes read-only and only the paths the simulator needs can
   be read (the Python installation, the package, the robot files, the renderer's libraries and devices,
   this process's own /proc entry); `/proc/<parent>/environ` and the user's files are out of reach;
3. seccomp-bpf (through `pyseccomp` over Debian's libseccomp): no new processes (threads are fine), no
   `execve`, no sockets, no opening files for writing or creating them, no renaming, deleting, linking or
   changing files, no signals to other processes, no ptrace, no io_uring (it would bypass the filter), no
   SysV or POSIX IPC objects (they outlive the process), no changes of priority, scheduling class or CPU
   affinity (but its own affinity), no raising of the limits from step 1.

seccomp also blocks writes where Landlock is missing; Landlock also blocks reads of secrets where seccomp
cannot look at paths. A layer the kernel lacks is reported in `LockdownReport.warnings` and logged loudly;
`HGEN_SANDBOX_STRICT=1` turns a missing layer into an error instead.

The environment is scrubbed separately (`scrubbed_environ`), before the worker's interpreter starts, so that
not even `/proc/self/environ` holds a secret.
"""

from __future__ import annotations

import errno
import logging
import os
import resource
import sys
from dataclasses import dataclass, field
from pathlib import Path

log = logging.getLogger(__name__)

ENV_STRICT = "HGEN_SANDBOX_STRICT"

# What MuJoCo, EGL/Mesa, the BLAS libraries, Python and the asset lookup read from the environment. Anything
# else (API keys, tokens, cloud credentials, SSH agents) never reaches a worker.
_ENV_KEEP = {"PATH", "LANG", "LANGUAGE", "TZ", "HOME", "TMPDIR", "LD_LIBRARY_PATH", "PYTHONHASHSEED",
             "MUJOCO_GL", "PYOPENGL_PLATFORM", "EGL_PLATFORM", "DISPLAY", "CUDA_VISIBLE_DEVICES",
             "NVIDIA_VISIBLE_DEVICES", "NVIDIA_DRIVER_CAPABILITIES", "__EGL_VENDOR_LIBRARY_FILENAMES",
             "__EGL_VENDOR_LIBRARY_DIRS", "__GLX_VENDOR_LIBRARY_NAME", "LP_NUM_THREADS", "OMP_NUM_THREADS",
             "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS", "XDG_CACHE_HOME", "HGEN_ASSETS", "HGEN_CACHE",
             "HGEN_FAMILIES_PATH", "HGEN_ROBOT", ENV_STRICT}
_ENV_KEEP_PREFIXES = ("LC_", "MESA_", "LIBGL_", "GALLIUM_", "OPENBLAS_", "GOTO_")
# Forced in every worker: caches that write are off instead of getting a hole in the wall, one BLAS thread
# (multithreaded OpenBLAS on small products is many times slower here, and threads are forked badly).
_ENV_FORCE = {"MESA_SHADER_CACHE_DISABLE": "true", "MESA_GLSL_CACHE_DISABLE": "true",
              "PYTHONDONTWRITEBYTECODE": "1", "PYTHONNOUSERSITE": "1"}
_ENV_DEFAULT = {"MUJOCO_GL": "egl", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def scrubbed_environ(environ: dict[str, str] | None = None) -> dict[str, str]:
    """The environment a worker gets: only what the simulator and renderer read, plus forced settings."""
    environ = dict(os.environ if environ is None else environ)
    out = {k: v for k, v in environ.items() if k in _ENV_KEEP or k.startswith(_ENV_KEEP_PREFIXES)}
    for k, v in _ENV_DEFAULT.items():
        out.setdefault(k, v)
    out.update(_ENV_FORCE)
    return out


@dataclass(frozen=True)
class Limits:
    """Per-worker resource limits (the parent adds wall-time limits per request)."""

    memory_bytes: int | None = 4 << 30  # address space; None: unlimited
    cpu_seconds: int | None = 3600  # CPU time of the whole worker (all of its threads)
    max_open_files: int = 1024


@dataclass
class LockdownReport:
    seccomp: bool = False
    landlock_abi: int = 0  # 0: not applied
    ipc_namespace: bool = False  # a fresh, empty IPC namespace (needs privilege; the filter refuses IPC anyway)
    threads_at_lockdown: int = 1
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"seccomp": self.seccomp, "landlock_abi": self.landlock_abi, "ipc_namespace": self.ipc_namespace,
                "threads_at_lockdown": self.threads_at_lockdown, "warnings": list(self.warnings)}


class LockdownError(RuntimeError):
    """A layer is missing and HGEN_SANDBOX_STRICT=1 asks for all of them."""


def lock_down(limits: Limits, read_paths: list[Path] | None = None) -> LockdownReport:
    """Lock this process down for good (see the module docstring); returns what was applied."""
    report = LockdownReport(threads_at_lockdown=_thread_count())
    if report.threads_at_lockdown > 1:
        # Landlock binds only the calling thread: a thread started earlier would stay free.
        report.warnings.append(f"{report.threads_at_lockdown} threads already run; Landlock binds only this one")
    sys.dont_write_bytecode = True
    _import_layers()  # libseccomp is found through ctypes.util, which runs ldconfig: only possible before
    _set_limits(limits)
    report.ipc_namespace = _unshare_ipc()
    try:
        report.landlock_abi = _apply_landlock(read_paths if read_paths is not None else default_read_paths())
    except Exception as e:  # noqa: BLE001 - any failure of this layer is reported, never silent
        report.warnings.append(f"Landlock not applied ({type(e).__name__}: {e}); files outside the workspace "
                               "stay readable")
    try:
        _apply_seccomp()
        report.seccomp = True
    except Exception as e:  # noqa: BLE001
        report.warnings.append(f"seccomp not applied ({type(e).__name__}: {e}); processes, sockets and file "
                               "writes are NOT blocked")
    for w in report.warnings:
        log.warning("plan worker lockdown incomplete: %s", w)
    if report.warnings and os.environ.get(ENV_STRICT) == "1":
        raise LockdownError("; ".join(report.warnings))
    return report


def _import_layers() -> None:
    import contextlib

    for name in ("pyseccomp", "landlock"):
        with contextlib.suppress(Exception):  # a missing layer is reported when it is applied
            __import__(name)


def _thread_count() -> int:
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        return 1


def _set_limits(limits: Limits) -> None:
    def both(which: int, value: int) -> None:
        resource.setrlimit(which, (value, value))

    if limits.memory_bytes is not None:
        both(resource.RLIMIT_AS, int(limits.memory_bytes))
    if limits.cpu_seconds is not None:
        both(resource.RLIMIT_CPU, int(limits.cpu_seconds))
    both(resource.RLIMIT_CORE, 0)
    both(resource.RLIMIT_NICE, 0)  # no raising its own priority (the calls are refused too, see _DENY)
    both(resource.RLIMIT_RTPRIO, 0)
    both(resource.RLIMIT_FSIZE, 0)  # a file opened for writing despite everything still cannot grow
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    cap = min(limits.max_open_files, hard if hard != resource.RLIM_INFINITY else limits.max_open_files)
    resource.setrlimit(resource.RLIMIT_NOFILE, (min(soft, cap), cap))


_CLONE_NEWIPC = 0x08000000


def _unshare_ipc() -> bool:
    """Move into a new IPC namespace where the kernel lets this process (root, or a user namespace): no other
    process's SysV objects or POSIX message queues are there, and whatever is made dies with the worker. Not a
    layer that must be there: seccomp refuses every IPC call anyway (`_DENY`)."""
    import ctypes

    try:
        return ctypes.CDLL(None, use_errno=True).unshare(_CLONE_NEWIPC) == 0
    except (OSError, AttributeError):
        return False


# -- Landlock ---------------------------------------------------------------------------------------------
def default_read_paths() -> list[Path]:
    """What a worker may read: Python and its packages, humanoidgen, the robot files and mesh cache, system
    libraries and the renderer's data and devices. Nothing under the user's home beyond those."""
    import humanoidgen

    paths: set[Path] = {Path(sys.prefix), Path(sys.base_prefix), Path(sys.exec_prefix),
                        Path(humanoidgen.__file__).resolve().parent}
    # Packages already imported from elsewhere (an editable install, the module holding a test's setup):
    # their own folder, or the single file of a plain module; never the folder around them (the current
    # directory or home, where a user's secrets live).
    tops: set[str] = set()  # each top-level package once: resolving thousands of module paths cost 0.1 s
    for mod in list(sys.modules.values()):
        f = getattr(mod, "__file__", None)
        if not isinstance(f, str) or getattr(mod, "__package__", None) is None:
            continue
        name = mod.__name__.split(".")[0]
        top = sys.modules.get(name)
        top_file = getattr(top, "__file__", None)
        if isinstance(top_file, str) and Path(top_file).name == "__init__.py":
            if name not in tops:
                tops.add(name)
                paths.add(Path(top_file).resolve().parent)
        else:
            paths.add(Path(f).resolve())
    try:
        from humanoidgen.assets.robot_files import cache_dir, resolve_assets_root

        paths.add(resolve_assets_root().resolve())
        paths.add(cache_dir().parent)  # decimated meshes (read only; the parent warms them)
    except Exception:  # noqa: BLE001 - no robot files yet: the episode will fail with its own message
        pass
    from humanoidgen.objects.family_data import extra_model_folders

    paths.update(extra_model_folders())  # object models added as files ($HGEN_FAMILIES_PATH), by family folder
    for p in ("/usr/lib", "/usr/lib64", "/lib", "/lib64", "/usr/share/glvnd", "/usr/share/egl",
              "/usr/share/drirc.d", "/usr/share/zoneinfo", "/etc/ld.so.cache", "/etc/localtime", "/etc/drirc",
              "/etc/glvnd", "/sys/devices/system/cpu", "/sys/devices/system/node", "/proc/cpuinfo",
              "/proc/meminfo", "/proc/stat", "/dev/null", "/dev/zero", "/dev/urandom", "/dev/random"):
        paths.add(Path(p))
    paths.add(Path(f"/proc/{os.getpid()}"))  # /proc/self, and no other process's entry
    kept = sorted(p for p in paths if p.exists())
    present = set(kept)
    return [p for p in kept if not any(q in present for q in p.parents)]  # one rule per subtree


_DEVICE_DIRS = ("/dev/dri",)
_DEVICE_GLOB = "nvidia*"  # NVIDIA's EGL opens its device files read-write and talks to them by ioctl


def _apply_landlock(read_paths: list[Path]) -> int:
    import landlock
    from landlock.plumbing import FSAccess, landlock_abi_version

    abi = landlock_abi_version()
    if abi < 1:
        raise OSError(errno.ENOSYS, "Landlock is not available in this kernel")
    rs = landlock.Ruleset(restrict_rules=FSAccess.all())
    read = FSAccess.READ_FILE | FSAccess.READ_DIR
    for p in read_paths:
        rights = read if p.is_dir() else FSAccess.READ_FILE
        rs.allow(str(p), rules=rights)
    device_rights = FSAccess.READ_FILE | FSAccess.WRITE_FILE | FSAccess.READ_DIR
    if abi >= 5:
        device_rights |= FSAccess.IOCTL_DEV
    for d in _DEVICE_DIRS:
        if os.path.isdir(d):
            rs.allow(d, rules=device_rights)
    for dev in sorted(Path("/dev").glob(_DEVICE_GLOB)):
        rs.allow(str(dev), rules=device_rights & ~FSAccess.READ_DIR if dev.is_char_device() else device_rights)
    rs.apply()
    return abi


# -- seccomp ----------------------------------------------------------------------------------------------
# Denied outright (EPERM): process creation and program loading, sockets, changes to the file system, other
# processes, kernel facilities that are not needed and widen the attack surface.
_DENY = (
    "execve", "execveat", "fork", "vfork",
    "socket", "socketpair", "connect", "bind", "listen", "accept", "accept4",
    "creat", "rename", "renameat", "renameat2", "unlink", "unlinkat", "mkdir", "mkdirat", "rmdir",
    "link", "linkat", "symlink", "symlinkat", "chmod", "fchmod", "fchmodat", "chown", "fchown", "lchown",
    "fchownat", "truncate", "mknod", "mknodat", "utime", "utimes", "utimensat", "futimesat",
    "setxattr", "lsetxattr", "fsetxattr", "removexattr", "lremovexattr", "fremovexattr",
    "mount", "umount2", "pivot_root", "chroot", "setns", "unshare", "swapon", "swapoff", "reboot",
    "kexec_load", "kexec_file_load", "init_module", "finit_module", "delete_module", "acct", "quotactl",
    "ptrace", "process_vm_readv", "process_vm_writev", "pidfd_getfd", "pidfd_send_signal", "tkill",
    "rt_sigqueueinfo", "rt_tgsigqueueinfo",
    "bpf", "perf_event_open", "userfaultfd", "io_uring_setup", "io_uring_enter", "io_uring_register",
    "keyctl", "add_key", "request_key", "name_to_handle_at", "open_by_handle_at", "fanotify_init",
    "setrlimit", "prlimit64", "capset", "personality", "sethostname", "setdomainname", "settimeofday",
    "clock_settime", "clock_adjtime", "adjtimex", "syslog", "vhangup", "iopl", "ioperm",
    "fsopen", "fsmount", "fsconfig", "fspick", "move_mount", "open_tree", "mount_setattr",
    "memfd_secret", "landlock_create_ruleset", "landlock_add_rule",
    # SysV and POSIX IPC: segments, queues and semaphore sets outlive the worker (SysV shm also lies outside
    # RLIMIT_AS), and another process's objects could be read. Rendering (EGL, surfaceless) uses none of it.
    "shmget", "shmat", "shmctl", "msgget", "msgsnd", "msgrcv", "msgctl", "semget", "semop", "semtimedop",
    "semctl", "ipc", "mq_open", "mq_unlink", "mq_timedsend", "mq_timedreceive", "mq_notify", "mq_getsetattr",
    # Scheduling: `who`/pid 0 names the process group for PRIO_PGRP, and as root a worker could give itself
    # SCHED_FIFO or nice -20 and starve the machine. Nothing the worker runs needs to change its priority.
    "setpriority", "sched_setscheduler", "sched_setparam", "sched_setattr", "ioprio_set",
)
# Answered "not implemented" so that libc falls back to a call the filter can inspect: clone3 passes its
# flags in memory (seccomp cannot read them; glibc then uses clone), openat2 passes open flags in memory.
_ENOSYS = ("clone3", "openat2")
# Each is matched as a whole: O_TMPFILE contains O_DIRECTORY's bit, which read-only directory opens use.
_O_WRITE_FLAGS = tuple(f for f in (os.O_WRONLY, os.O_RDWR, os.O_CREAT, os.O_TRUNC, os.O_APPEND,
                                   getattr(os, "O_TMPFILE", 0)) if f)
_CLONE_THREAD = 0x00010000
_TIOCSTI, _TIOCLINUX = 0x5412, 0x541C
_PR_SET_PDEATHSIG = 1


def _apply_seccomp() -> None:
    import pyseccomp as sc

    f = sc.SyscallFilter(defaction=sc.ALLOW)
    eperm = sc.ERRNO(errno.EPERM)
    for name in _DENY:
        _rule(f, eperm, name)
    for name in _ENOSYS:
        _rule(f, sc.ERRNO(errno.ENOSYS), name)
    # clone without CLONE_THREAD makes a process: denied. Threads (pthread_create) stay allowed.
    _rule(f, eperm, "clone", sc.Arg(0, sc.MASKED_EQ, _CLONE_THREAD, 0))
    # Opening for writing, creating, truncating or appending: denied; read-only opens stay allowed.
    for flag in _O_WRITE_FLAGS:
        _rule(f, eperm, "open", sc.Arg(1, sc.MASKED_EQ, flag, flag))
        _rule(f, eperm, "openat", sc.Arg(2, sc.MASKED_EQ, flag, flag))
    # Signals only to this process (and its own threads).
    pid = os.getpid()
    _rule(f, eperm, "kill", sc.Arg(0, sc.NE, pid))
    _rule(f, eperm, "tgkill", sc.Arg(0, sc.NE, pid))
    # Pinning or moving the memory of other processes (the fork server, the parent): only this process (0).
    for name in ("sched_setaffinity", "migrate_pages", "move_pages"):
        _rule(f, eperm, name, sc.Arg(0, sc.NE, 0))
    # Clearing or changing the parent-death signal the worker set (it would outlive `hgen`, see `lifeline`).
    _rule(f, eperm, "prctl", sc.Arg(0, sc.EQ, _PR_SET_PDEATHSIG))
    # Typing into the controlling terminal.
    _rule(f, eperm, "ioctl", sc.Arg(1, sc.EQ, _TIOCSTI))
    _rule(f, eperm, "ioctl", sc.Arg(1, sc.EQ, _TIOCLINUX))
    f.load()


def _rule(f, action: int, name: str, *args) -> None:
    """Add one rule; a call this architecture does not have (e.g. `open` on arm64) has nothing to deny.
    Any other failure propagates, so that a filter missing a rule is reported, never silently loaded."""
    import pyseccomp as sc

    if sc.resolve_syscall(sc.system_arch(), name) < 0:
        return
    f.add_rule(action, name, *args)
